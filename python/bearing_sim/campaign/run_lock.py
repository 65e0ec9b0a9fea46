"""One owner per run: an invocation holds a POSIX byte-range lock on bytes [A, B) of
DIR/campaign.lock for its runs A..B-1, so that two processes never generate the same run in
one --out (each would remove the other's temporary files and compute the run again), while
job-array tasks with disjoint index ranges share the directory. The kernel drops the lock
when the process ends, however it ends. fcntl locks hold across NFS too."""
import errno
import fcntl
import os
import struct

from .errors import CampaignError, OutputError

LOCK_FILE = 'campaign.lock'
_FLOCK = '@hhqqi4x'  # Linux struct flock: type, whence, start, len, pid (and padding)


class RunLock:
    """Holds runs `indices` (a range) of the campaign in `out_dir` until released."""

    def __init__(self, out_dir, indices):
        self.path = os.path.join(out_dir, LOCK_FILE)
        try:
            self._fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as e:
            raise OutputError(f'cannot open {self.path}: {e.strerror}') from None
        try:
            fcntl.lockf(self._fd, fcntl.LOCK_EX | fcntl.LOCK_NB, len(indices), indices.start)
        except OSError as e:
            holder = self._holder(indices) if e.errno in (errno.EACCES, errno.EAGAIN) else None
            os.close(self._fd)
            if holder is None:
                raise OutputError(f'cannot lock {self.path}: {e.strerror}') from None
            last = indices.stop - 1
            raise CampaignError(
                f'--out {out_dir}: another bearing_campaign process{holder} is generating runs of {indices.start}..'
                f'{last} there (lock {self.path}); wait for it to end, or give this one another --out or an '
                f'--index-range it does not hold') from None

    def _holder(self, indices):
        """' (PID n)' of a process holding part of the range, when the kernel tells it."""
        query = struct.pack(_FLOCK, fcntl.F_WRLCK, os.SEEK_SET, indices.start, len(indices), 0)
        try:
            lock_type, _, _, _, pid = struct.unpack(_FLOCK, fcntl.fcntl(self._fd, fcntl.F_GETLK, query))
        except OSError:
            return ''
        return f' (PID {pid})' if lock_type != fcntl.F_UNLCK and pid > 0 else ''

    def release(self):
        if self._fd is not None:
            os.close(self._fd)  # closing drops the process's locks on the file
            self._fd = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.release()
