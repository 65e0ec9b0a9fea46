#include "command_runner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

extern char** environ;

namespace bearing_sim::test {
namespace {

constexpr int kKillAfterS = 10;  // SIGKILL this long after the SIGTERM

// Appends what `fd` has to `into`; false at end of file.
bool read_some(int fd, std::string& into) {
  char buffer[65536];
  const ssize_t n = ::read(fd, buffer, sizeof buffer);
  if (n > 0) into.append(buffer, static_cast<std::size_t>(n));
  return n > 0 || (n < 0 && (errno == EINTR || errno == EAGAIN));
}

}  // namespace

CommandResult run_command(const std::string& command, int timeout_s) {
  CommandResult r;
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) {
    r.err = std::string("[run_command] pipe: ") + std::strerror(errno) + "\n";
    return r;
  }
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    r.err = std::string("[run_command] pipe: ") + std::strerror(errno) + "\n";
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    return r;
  }
  // posix_spawn, not fork: the ROS tests call this with their spinner threads running.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  std::vector<std::string> args = {
      "timeout", "--kill-after=" + std::to_string(kKillAfterS), std::to_string(timeout_s), "/bin/sh", "-c", command};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, "timeout", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (spawned != 0) {
    ::close(out_pipe[0]);
    ::close(err_pipe[0]);
    r.err = std::string("[run_command] cannot start coreutils' timeout: ") + std::strerror(spawned) + "\n";
    return r;
  }

  // Both pipes read as the data comes (a full stderr pipe must not block the child).
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  std::string* into[2] = {&r.out, &r.err};
  int open_pipes = 2;
  // timeout ends the command's process group by timeout_s + kKillAfterS; a descendant that
  // left the group may still hold a pipe open: reading stops 30 s after that.
  const auto give_up = start + std::chrono::seconds(timeout_s + kKillAfterS + 30);
  while (open_pipes > 0 && std::chrono::steady_clock::now() < give_up) {
    if (::poll(fds, 2, 1000) < 0 && errno != EINTR) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
      if (!read_some(fds[i].fd, *into[i])) {
        ::close(fds[i].fd);
        fds[i].fd = -1;  // poll ignores it from now on
        --open_pipes;
      }
    }
  }
  for (pollfd& f : fds)
    if (f.fd >= 0) ::close(f.fd);
  int status = 0;
  if (open_pipes > 0 && ::waitpid(pid, &status, WNOHANG) == 0) ::kill(pid, SIGKILL);  // timeout itself hangs
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // 124 / 137 from the command itself (not stopped) come back before the time-out.
  if ((r.exit_code == 124 || r.exit_code == 137) && elapsed_s >= timeout_s)
    r.err +=
        "\n[run_command] " + command + ": did not finish within " + std::to_string(timeout_s) + " s and was stopped\n";
  return r;
}

}  // namespace bearing_sim::test
