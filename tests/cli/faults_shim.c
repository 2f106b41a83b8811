/* Fault injection for tests/cli/faults.sh, loaded with LD_PRELOAD: a write to a file whose path contains
 * FAULT_PATH fails as on a full disk (ENOSPC), or kills the process (SIGKILL) in the middle of the write.
 * Nothing in fluidbed knows about it; it stands in for a full disk or a batch system's kill -9 without root.
 *
 *   FAULT_PATH=<substring>  the files it acts on (the path as /proc/self/fd shows it, temporaries included)
 *   FAULT_AFTER=<n>         act on the n-th write() / pwrite() to such a file (default 1); every later one to a
 *                           matching file fails too (a full disk stays full)
 *   FAULT_ACTION=enospc     (default) the write fails with errno ENOSPC; with FAULT_PARTIAL=1 the n-th call
 *                           first writes half of its buffer, as a disk that fills up in the middle of a call
 *   FAULT_ACTION=kill       half of the n-th write reaches the file, then the process is killed with SIGKILL
 *
 * Built by the test itself: cc -shared -fPIC -o faults_shim.so faults_shim.c -ldl
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

static long count;
static int fired;

static int matches(int fd) {
  const char *pattern = getenv("FAULT_PATH");
  char link[64], target[4096];
  ssize_t n;
  if (pattern == NULL || *pattern == '\0') return 0;
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  n = readlink(link, target, sizeof target - 1);
  if (n < 0) return 0;
  target[n] = '\0';
  return strstr(target, pattern) != NULL;
}

/* 0: write normally; 1: fail with ENOSPC; 2: write half, then fail or kill (see the header). */
static int decide(int fd, size_t size) {
  const char *after = getenv("FAULT_AFTER");
  const char *action = getenv("FAULT_ACTION");
  const char *partial = getenv("FAULT_PARTIAL");
  if (!matches(fd)) return 0;
  if (fired) return 1;
  if (++count < (after ? atol(after) : 1)) return 0;
  fired = 1;
  if (action != NULL && strcmp(action, "kill") == 0) return 2;
  return (partial != NULL && strcmp(partial, "1") == 0 && size > 1) ? 2 : 1;
}

static int kill_now(void) {
  const char *action = getenv("FAULT_ACTION");
  return action != NULL && strcmp(action, "kill") == 0;
}

ssize_t write(int fd, const void *buf, size_t size) {
  static ssize_t (*real)(int, const void *, size_t);
  if (real == NULL) real = (ssize_t(*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
  switch (decide(fd, size)) {
    case 1: errno = ENOSPC; return -1;
    case 2: {
      const ssize_t n = real(fd, buf, size / 2);
      if (kill_now()) kill(getpid(), SIGKILL);
      return n;
    }
    default: return real(fd, buf, size);
  }
}

static ssize_t positioned(const char *name, int fd, const void *buf, size_t size, off_t offset) {
  ssize_t (*real)(int, const void *, size_t, off_t) =
      (ssize_t(*)(int, const void *, size_t, off_t))dlsym(RTLD_NEXT, name);
  switch (decide(fd, size)) {
    case 1: errno = ENOSPC; return -1;
    case 2: {
      const ssize_t n = real(fd, buf, size / 2, offset);
      if (kill_now()) kill(getpid(), SIGKILL);
      return n;
    }
    default: return real(fd, buf, size, offset);
  }
}

ssize_t pwrite(int fd, const void *buf, size_t size, off_t offset) { return positioned("pwrite", fd, buf, size, offset); }
ssize_t pwrite64(int fd, const void *buf, size_t size, off_t offset) {
  return positioned("pwrite64", fd, buf, size, offset);
}
