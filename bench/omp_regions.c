// Counts the OpenMP parallel regions a run opens and the wall time the calling thread spends inside them
// (bench/omp_regions.sh, docs/performance.md section 34). Preloaded, it stands between the program and libgomp's
// two region entries that GCC emits here (GOMP_parallel for `parallel` and `parallel for`, GOMP_parallel_sections);
// the regions are told apart by their outlined function, whose offset in the executable the script names with nm.
// Each region's body is run through a timer on every thread of its team. At exit it writes, to $OMP_REGIONS_OUT:
// the process wall time, then one row per outlined function: calls, calls that ran on one thread (an `if` clause
// false, or nested), calls inside another region; for the outermost calls on a team the seconds the calling thread
// spent in the region and the seconds its threads spent in the body, summed; for those on one thread their seconds.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

typedef void (*body_fn)(void *);
typedef void (*parallel_fn)(body_fn, void *, unsigned, unsigned);
typedef void (*sections_fn)(body_fn, void *, unsigned, unsigned, unsigned);

enum { kSlots = 4096, kThreads = 256 };
struct slot {
  uintptr_t fn;
  unsigned long calls, single, nested;
  double seconds, busy;  // outermost calls on a team: the region's wall on the calling thread, the team's work
  double alone;          // outermost calls on one thread: their wall
};
static struct slot slots[kSlots];
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static double started;
static __thread int depth;  // regions this thread is running a body of

int omp_get_thread_num(void);
int omp_get_num_threads(void);

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

// One call of a region: the real body and its data, and each thread's time in it.
struct call {
  body_fn fn;
  void *data;
  int team;
  double busy[kThreads];
};

static void timed_body(void *p) {
  struct call *c = p;
  const int me = omp_get_thread_num();
  if (me == 0) c->team = omp_get_num_threads();
  ++depth;
  const double t0 = now();
  c->fn(c->data);
  if (me < kThreads) c->busy[me] = now() - t0;
  --depth;
}

static void record(const struct call *c, int nested, double seconds) {
  double busy = 0.0;
  for (int k = 0; k < c->team && k < kThreads; ++k) busy += c->busy[k];
  pthread_mutex_lock(&lock);
  uintptr_t key = (uintptr_t)c->fn;
  size_t k = (size_t)((key >> 4) % kSlots);
  while (slots[k].fn != 0 && slots[k].fn != key) k = (k + 1) % kSlots;
  slots[k].fn = key;
  slots[k].calls += 1;
  slots[k].single += c->team == 1;
  slots[k].nested += nested;
  if (!nested && c->team == 1) slots[k].alone += seconds;
  if (!nested && c->team > 1) {
    slots[k].seconds += seconds;
    slots[k].busy += busy;
  }
  pthread_mutex_unlock(&lock);
}

void GOMP_parallel(body_fn fn, void *data, unsigned threads, unsigned flags) {
  static parallel_fn real;
  if (!real) real = (parallel_fn)dlsym(RTLD_NEXT, "GOMP_parallel");
  struct call c = {fn, data, 1, {0.0}};
  const int nested = depth > 0;
  const double t0 = now();
  real(timed_body, &c, threads, flags);
  record(&c, nested, now() - t0);
}

void GOMP_parallel_sections(body_fn fn, void *data, unsigned threads, unsigned count, unsigned flags) {
  static sections_fn real;
  if (!real) real = (sections_fn)dlsym(RTLD_NEXT, "GOMP_parallel_sections");
  struct call c = {fn, data, 1, {0.0}};
  const int nested = depth > 0;
  const double t0 = now();
  real(timed_body, &c, threads, count, flags);
  record(&c, nested, now() - t0);
}

__attribute__((constructor)) static void begin(void) { started = now(); }

// Offsets from the executable's load address, so that nm's symbol addresses name them.
__attribute__((destructor)) static void end(void) {
  const char *path = getenv("OMP_REGIONS_OUT");
  FILE *out = path ? fopen(path, "w") : NULL;
  if (!out) return;
  uintptr_t base = 0;
  for (size_t k = 0; k < kSlots && base == 0; ++k) {
    Dl_info info;
    if (slots[k].fn != 0 && dladdr((void *)slots[k].fn, &info) != 0) base = (uintptr_t)info.dli_fbase;
  }
  fprintf(out, "wall_s %.6f\n", now() - started);
  for (size_t k = 0; k < kSlots; ++k)
    if (slots[k].fn != 0)
      fprintf(out, "%lx %lu %lu %lu %.6f %.6f %.6f\n", (unsigned long)(slots[k].fn - base), slots[k].calls,
              slots[k].single, slots[k].nested, slots[k].seconds, slots[k].busy, slots[k].alone);
  fclose(out);
}
