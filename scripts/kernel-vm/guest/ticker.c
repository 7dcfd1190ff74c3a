// The VM's stand-in for the FPGA tick: a square wave on a gpio-sim input
// line, made by writing its sysfs `pull` attribute (pull-up = high).
// While HOLD_FILE exists the line stays low and HELD_FILE is created, so
// the harness can make single edges itself (lib.sh tick_step).
// Built by scripts/kernel-vm/run.sh with the host's gcc (a bash loop costs
// too much CPU per edge under TCG).
// Usage: ticker PULL_PATH PERIOD_US HOLD_FILE HELD_FILE
#define _GNU_SOURCE
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static void level(int fd, int high) {
  const char* v = high ? "pull-up" : "pull-down";
  if (pwrite(fd, v, strlen(v), 0) < 0) perror("ticker: write pull");
}

// Next deadline; a deadline already past (the VM was starved) restarts
// from now rather than making a burst of edges.
static void advance(struct timespec* t, long ns) {
  t->tv_nsec += ns;
  while (t->tv_nsec >= 1000000000L) { t->tv_nsec -= 1000000000L; t->tv_sec++; }
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  if (t->tv_sec < now.tv_sec || (t->tv_sec == now.tv_sec && t->tv_nsec < now.tv_nsec)) *t = now;
}

int main(int argc, char** argv) {
  if (argc != 5) { fprintf(stderr, "usage: ticker PULL_PATH PERIOD_US HOLD_FILE HELD_FILE\n"); return 2; }
  const int fd = open(argv[1], O_WRONLY | O_CLOEXEC);
  if (fd < 0) { perror(argv[1]); return 1; }
  const long half_ns = atol(argv[2]) * 500L;
  if (half_ns <= 0) { fprintf(stderr, "ticker: bad period\n"); return 2; }
  struct timespec next;
  clock_gettime(CLOCK_MONOTONIC, &next);
  int held = 0;
  for (;;) {
    if (access(argv[3], F_OK) == 0) {
      if (!held) { close(open(argv[4], O_WRONLY | O_CREAT | O_CLOEXEC, 0644)); held = 1; }
    } else {
      if (held) { unlink(argv[4]); held = 0; }
      level(fd, 1);
    }
    advance(&next, half_ns);
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
    if (!held) level(fd, 0);
    advance(&next, half_ns);
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
  }
}
