/* A fault injector loaded with LD_PRELOAD into `kappa`: it fails the Nth call
 * of one family of system calls, as a full disk, a failing device or a lost
 * permission would.
 *
 *   KAPPA_FAULT=write:N   the Nth write()/writev()   fails with ENOSPC
 *   KAPPA_FAULT=fsync:N   the Nth fsync()/fdatasync() fails with EIO
 *   KAPPA_FAULT=rename:N  the Nth rename()/renameat()/linkat() fails with EACCES
 *   KAPPA_FAULT=open:N    the Nth open()/openat()/fopen() fails with EACCES
 *   KAPPA_FAULT=count     nothing fails; the calls of each family are counted
 *
 * With KAPPA_FAULT_COUNTS=FILE the counts are written to FILE at exit
 * ("write N\nfsync N\nrename N\nopen N\n"), so a test knows how many N to try.
 * With KAPPA_FAULT_NO_TMPFILE=1, every open with O_TMPFILE fails with
 * EOPNOTSUPP, as on a file system without unnamed files.
 *
 * Only calls made through the dynamic linker are seen: Kappa's, libstdc++'s
 * (so OpenEXR's), not those the C library makes inside itself (libpng writes
 * with fwrite: a PNG's writes are not failed, its fsync and rename are). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

enum family { WRITE, FSYNC, RENAME, OPEN, FAMILIES };
static const char* const names[FAMILIES] = {"write", "fsync", "rename", "open"};
static const int errors[FAMILIES] = {ENOSPC, EIO, EACCES, EACCES};

static atomic_long calls[FAMILIES];
static int target_family = -1;
static long target_call = 0;

static void write_counts(void) {
  const char* file = getenv("KAPPA_FAULT_COUNTS");
  if (!file) return;
  FILE* f = fopen(file, "w");
  if (!f) return;
  for (int i = 0; i < FAMILIES; ++i) fprintf(f, "%s %ld\n", names[i], (long)atomic_load(&calls[i]));
  fclose(f);
}

__attribute__((constructor)) static void read_plan(void) {
  const char* plan = getenv("KAPPA_FAULT");
  if (plan) {
    for (int i = 0; i < FAMILIES; ++i) {
      const size_t n = strlen(names[i]);
      if (strncmp(plan, names[i], n) == 0 && plan[n] == ':') {
        target_family = i;
        target_call = atol(plan + n + 1);
      }
    }
  }
  atexit(write_counts);
}

/* Whether this call of `family` is the one to fail (errno set). */
/* Whether an open with these flags is refused as unnamed (errno set). */
static int no_tmpfile(int flags) {
  if (!(flags & __O_TMPFILE) || !getenv("KAPPA_FAULT_NO_TMPFILE")) return 0;
  errno = EOPNOTSUPP;
  return 1;
}

static int fails(enum family family) {
  const long n = atomic_fetch_add(&calls[family], 1) + 1;
  if ((int)family != target_family || n != target_call) return 0;
  errno = errors[family];
  return 1;
}

#define REAL(name) ((__typeof__(&name))dlsym(RTLD_NEXT, #name))

ssize_t write(int fd, const void* buf, size_t count) {
  if (fails(WRITE)) return -1;
  return REAL(write)(fd, buf, count);
}

ssize_t writev(int fd, const struct iovec* parts, int count) {
  if (fails(WRITE)) return -1;
  return REAL(writev)(fd, parts, count);
}

int fsync(int fd) {
  if (fails(FSYNC)) return -1;
  return REAL(fsync)(fd);
}

int fdatasync(int fd) {
  if (fails(FSYNC)) return -1;
  return REAL(fdatasync)(fd);
}

int rename(const char* from, const char* to) {
  if (fails(RENAME)) return -1;
  return REAL(rename)(from, to);
}

int renameat(int from_dir, const char* from, int to_dir, const char* to) {
  if (fails(RENAME)) return -1;
  return REAL(renameat)(from_dir, from, to_dir, to);
}

int linkat(int from_dir, const char* from, int to_dir, const char* to, int flags) {
  if (fails(RENAME)) return -1;
  return REAL(linkat)(from_dir, from, to_dir, to, flags);
}

/* open and openat take a mode only with O_CREAT or O_TMPFILE. */
#define MODE_OF(flags, mode)                                    \
  do {                                                          \
    if ((flags) & (O_CREAT | __O_TMPFILE)) {                    \
      va_list args;                                             \
      va_start(args, flags);                                    \
      mode = va_arg(args, int);                                 \
      va_end(args);                                             \
    }                                                           \
  } while (0)

int open(const char* path, int flags, ...) {
  int mode = 0;
  MODE_OF(flags, mode);
  if (no_tmpfile(flags) || fails(OPEN)) return -1;
  return REAL(open)(path, flags, mode);
}

int open64(const char* path, int flags, ...) {
  int mode = 0;
  MODE_OF(flags, mode);
  if (no_tmpfile(flags) || fails(OPEN)) return -1;
  return REAL(open64)(path, flags, mode);
}

int openat(int dir, const char* path, int flags, ...) {
  int mode = 0;
  MODE_OF(flags, mode);
  if (no_tmpfile(flags) || fails(OPEN)) return -1;
  return REAL(openat)(dir, path, flags, mode);
}

FILE* fopen(const char* path, const char* how) {
  if (fails(OPEN)) return NULL;
  return REAL(fopen)(path, how);
}

FILE* fopen64(const char* path, const char* how) {
  if (fails(OPEN)) return NULL;
  return REAL(fopen64)(path, how);
}
