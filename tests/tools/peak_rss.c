/* peak_rss FILE PROGRAM [ARG...]: runs PROGRAM and writes its own peak resident set (KiB, from
 * wait4's ru_maxrss) to FILE; exits with PROGRAM's status (128 + the signal that ended it).
 *
 * Why a program of its own: a test that forks and execs the program reads, through wait4, a peak
 * that includes the test process's own resident set at the fork (the child's copy of the parent's
 * address space carries its high-water mark across exec). This program is small: the program it
 * forks starts from its few hundred KiB, so the figure is the measured program's own (issue #44,
 * finding 9). */
#include <stdio.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: peak_rss FILE PROGRAM [ARG...]\n");
    return 127;
  }
  const pid_t pid = fork();
  if (pid < 0) return 127;
  if (pid == 0) {
    execvp(argv[2], argv + 2);
    _exit(127);
  }
  int status = 0;
  struct rusage usage;
  if (wait4(pid, &status, 0, &usage) != pid) return 127;
  FILE* f = fopen(argv[1], "w");
  if (f == NULL) return 127;
  fprintf(f, "%ld\n", usage.ru_maxrss);
  fclose(f);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
