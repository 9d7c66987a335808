/* An LD_PRELOAD library for the tests that kill a writer at a rename: every
 * rename(), renameat() and renameat2() of the process is counted (appended
 * to the file HI_RENAME_LOG names, when set), and the one numbered
 * HI_KILL_AT_RENAME (1-based) ends the process with SIGKILL before it
 * happens. Not part of the product: tests/unit/cli/cli_results_test.cc. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>

static int renames;

static void Count(void) {
  const int n = __atomic_add_fetch(&renames, 1, __ATOMIC_SEQ_CST);
  const char* log = getenv("HI_RENAME_LOG");
  if (log) {
    FILE* f = fopen(log, "a");
    if (f) {
      fprintf(f, "%d\n", n);
      fclose(f);
    }
  }
  const char* at = getenv("HI_KILL_AT_RENAME");
  if (at && atoi(at) == n) raise(SIGKILL);
}

int rename(const char* from, const char* to) {
  Count();
  int (*real)(const char*, const char*) = (int (*)(const char*, const char*))dlsym(RTLD_NEXT, "rename");
  return real(from, to);
}

int renameat(int from_dir, const char* from, int to_dir, const char* to) {
  Count();
  int (*real)(int, const char*, int, const char*) =
      (int (*)(int, const char*, int, const char*))dlsym(RTLD_NEXT, "renameat");
  return real(from_dir, from, to_dir, to);
}

int renameat2(int from_dir, const char* from, int to_dir, const char* to, unsigned int flags) {
  Count();
  int (*real)(int, const char*, int, const char*, unsigned int) =
      (int (*)(int, const char*, int, const char*, unsigned int))dlsym(RTLD_NEXT, "renameat2");
  return real(from_dir, from, to_dir, to, flags);
}
