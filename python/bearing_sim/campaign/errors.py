"""The errors that stop a campaign (the command exits 2 on them)."""


class CampaignError(ValueError):
    """A campaign file or output directory that cannot be used; the message names the file and the key."""


class OutputError(CampaignError):
    """A file of the output directory that cannot be written (a full disk, a read-only file system):
    not a failure of the run, so the campaign stops instead of recording every later run as failed."""
