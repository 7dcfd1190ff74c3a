#pragma once
// The system-call guard of the tick-discipline tests: body() runs in a
// forked child under a seccomp filter that allows only exit / exit_group
// and kills the process on any other system call (so the code under test
// can neither block on a lock, sleep, log nor do I/O).
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstddef>

namespace tnv::test {

inline constexpr int kSeccompUnavailable = 77;

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSeccompUsable = false;  // the sanitizer runtime makes its own system calls
#else
inline constexpr bool kSeccompUsable = true;
#endif

// The child's exit code (body()'s return value), -signal if it was killed
// (-SIGSYS: a system call), or kSeccompUnavailable.
template <typename Body>
int run_without_syscalls(Body body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    struct sock_filter filter[] = {
        BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_exit_group, 0, 1),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_exit, 0, 1),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS),
    };
    struct sock_fprog prog = {static_cast<unsigned short>(sizeof filter / sizeof filter[0]), filter};
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) ::_exit(kSeccompUnavailable);
    if (::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog) != 0) ::_exit(kSeccompUnavailable);
    const int code = body();
    ::syscall(SYS_exit_group, code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? -WTERMSIG(status) : -1000;
}

}  // namespace tnv::test
