/* warnings_c: checks that the server's plausibility warnings reach a C
 * caller (rc_wheel_forces.n_warnings, rc_step_warning), for
 * tests/end_to_end/cpp_client.rs.
 *
 * On the built-in pair with Hertz+FASTSIM, 3 mm to the right at 30 m/s and
 * 60 kN a wheel, it solves
 *   step 0: the server's default pitch rate, no roll given (plausible),
 *   step 1: the pitch rate PITCH_FACTOR times -V / 0.46 m prescribed, far
 *           from free rolling (the server warns LONGITUDINAL_FORCE),
 *   step 2: the roll ROLL_RAD prescribed, which leaves the left wheel above
 *           its rail (the server warns APPROACH),
 * then rolls back to step 1 and solves step 2 again as step 0 (plausible).
 * It prints on stdout, for each step, "step=K label=L n_warnings=N" (L:
 * plausible, pitch, roll, again) and then per warning "warning step=K
 * index=I kind=.. side=.. value=.. limit=.. message=TEXT" (the message
 * last, to the end of the line), for the test
 * to check against the server's figures. It checks here what does not need
 * them: bad indices and a NULL session refused with RC_ERR_USAGE and the
 * outputs unchanged, NULL outputs accepted, truncated messages, warnings
 * kept over a refused step and a rollback, cleared by a plausible step.
 * Exits 0 when all hold, 1 (with "FAIL: ..." on stderr) otherwise.
 *
 * Usage: warnings_c TARGET */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "railcontact_c.h"

#define SPEED_M_PER_S 30.0
#define NOMINAL_RADIUS_M 0.46
#define PITCH_FACTOR 1.05
#define ROLL_RAD 0.001

static int failures = 0;

static void fail(const char* what, long step, int rc, const char* err) {
  fprintf(stderr, "FAIL: %s (step %ld, rc %d: %s)\n", what, step, rc, err);
  ++failures;
}

/* Prints step k's warnings and checks rc_step_warning's contract on them. */
static void report(rc_session* s, long k, const char* label, const rc_wheel_forces* out) {
  char message[1024], small[16], err[256];
  printf("step=%ld label=%s n_warnings=%d\n", k, label, (int)out->n_warnings);
  for (int32_t i = 0; i < out->n_warnings; ++i) {
    int32_t kind = 0, side = 99;
    double value = 0.0, limit = 0.0;
    int rc = rc_step_warning(s, i, &kind, &side, &value, &limit, message, sizeof message, err,
                             sizeof err);
    if (rc != 0) {
      fail("rc_step_warning of an index below n_warnings", k, rc, err);
      continue;
    }
    if (strlen(message) + 1 >= sizeof message) fail("message filled the 1024 bytes", k, 0, "");
    printf("warning step=%ld index=%d kind=%d side=%d value=%.17g limit=%.17g message=%s\n", k,
           (int)i, (int)kind, (int)side, value, limit, message);
    /* Truncated into 16 bytes: the first 15 and a NUL (the text is ASCII). */
    memset(small, 'x', sizeof small);
    rc = rc_step_warning(s, i, NULL, NULL, NULL, NULL, small, sizeof small, err, sizeof err);
    if (rc != 0 || small[sizeof small - 1] != '\0' || strlen(small) != sizeof small - 1 ||
        strncmp(small, message, sizeof small - 1) != 0)
      fail("message truncated into 16 bytes", k, rc, small);
    /* One byte: the empty string. */
    small[0] = 'x';
    rc = rc_step_warning(s, i, NULL, NULL, NULL, NULL, small, 1, NULL, 0);
    if (rc != 0 || small[0] != '\0') fail("message into 1 byte", k, rc, "");
  }
  /* Beyond the last, and negative: refused, outputs untouched. */
  const int32_t bad[2] = {out->n_warnings, -1};
  for (int b = 0; b < 2; ++b) {
    int32_t kind = 77, side = 77;
    double value = 7.0, limit = 7.0;
    strcpy(message, "untouched");
    err[0] = '\0';
    int rc = rc_step_warning(s, bad[b], &kind, &side, &value, &limit, message, sizeof message,
                             err, sizeof err);
    if (rc != RC_ERR_USAGE || err[0] == '\0' || kind != 77 || side != 77 || value != 7.0 ||
        limit != 7.0 || strcmp(message, "untouched") != 0)
      fail("a bad index refused with RC_ERR_USAGE, outputs unchanged", k, rc, err);
  }
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s TARGET\n", argv[0]);
    return 2;
  }
  char err[1024];
  int rc = rc_step_warning(NULL, 0, NULL, NULL, NULL, NULL, NULL, 0, err, sizeof err);
  if (rc != RC_ERR_USAGE) fail("a NULL session refused with RC_ERR_USAGE", -1, rc, err);

  rc_session* s = rc_open(argv[1], "mbench_s1002_uic60", RC_MODEL_HERTZ_FASTSIM, err, sizeof err);
  if (s == NULL) {
    fprintf(stderr, "FAIL: rc_open: %s\n", err);
    return 1;
  }
  rc = rc_step_warning(s, 0, NULL, NULL, NULL, NULL, NULL, 0, err, sizeof err);
  if (rc != RC_ERR_USAGE) fail("no warning before the first step", -1, rc, err);

  rc_wheelset_state in;
  memset(&in, 0, sizeof in);
  in.lateral_m = 0.003;
  in.forward_m_per_s = SPEED_M_PER_S;
  in.vertical_force_n = 60e3;
  rc_wheel_forces out;
  long k = 0;

  /* Step 0: plausible. */
  rc = rc_step(s, (uint64_t)k, 0.0, &in, &out, err, sizeof err);
  if (rc != 0) fail("rc_step", k, rc, err);
  report(s, k, "plausible", &out);

  /* Step 1: a pitch rate 5 % off -V / r0, marked. */
  ++k;
  in.has_pitch_rad_per_s = 1;
  in.pitch_rad_per_s = -SPEED_M_PER_S / NOMINAL_RADIUS_M * PITCH_FACTOR;
  in.mark = 1;
  rc = rc_step(s, (uint64_t)k, 1e-3, &in, &out, err, sizeof err);
  if (rc != 0) fail("rc_step", k, rc, err);
  report(s, k, "pitch", &out);
  in.has_pitch_rad_per_s = 0;
  in.pitch_rad_per_s = 0.0;
  in.mark = 0;

  /* Step 2: a roll that leaves the left wheel above its rail. */
  ++k;
  in.has_roll_rad = 1;
  in.roll_rad = ROLL_RAD;
  rc = rc_step(s, (uint64_t)k, 2e-3, &in, &out, err, sizeof err);
  if (rc != 0) fail("rc_step", k, rc, err);
  report(s, k, "roll", &out);
  in.has_roll_rad = 0;
  in.roll_rad = 0.0;
  const int32_t n2 = out.n_warnings;
  int32_t kind2 = 0;
  rc_step_warning(s, 0, &kind2, NULL, NULL, NULL, NULL, 0, NULL, 0);

  /* A refused step (wrong index) and a rollback keep step 2's warnings. */
  rc_wheel_forces refused;
  rc = rc_step(s, (uint64_t)(k + 5), 3e-3, &in, &refused, err, sizeof err);
  if (rc != 9) fail("an out-of-order step refused with FAILED_PRECONDITION", k + 5, rc, err);
  int32_t kind = 0;
  rc = rc_step_warning(s, n2 - 1, &kind, NULL, NULL, NULL, NULL, 0, err, sizeof err);
  if (n2 > 0 && (rc != 0 || (n2 == 1 && kind != kind2)))
    fail("warnings kept over a refused step", k, rc, err);
  uint64_t next = 0;
  rc = rc_rollback(s, 1, &next, err, sizeof err);
  if (rc != 0 || next != 2) fail("rc_rollback to step 1", 1, rc, err);
  rc = rc_step_warning(s, n2 - 1, &kind, NULL, NULL, NULL, NULL, 0, err, sizeof err);
  if (n2 > 0 && (rc != 0 || (n2 == 1 && kind != kind2)))
    fail("warnings kept over a rollback", k, rc, err);

  /* Step 2 again, plausible: no warnings, the old ones gone. */
  rc = rc_step(s, (uint64_t)k, 2e-3, &in, &out, err, sizeof err);
  if (rc != 0) fail("rc_step", k, rc, err);
  report(s, k, "again", &out);
  rc = rc_step_warning(s, 0, NULL, NULL, NULL, NULL, NULL, 0, err, sizeof err);
  if (out.n_warnings == 0 && rc != RC_ERR_USAGE)
    fail("a plausible step clears the warnings", k, rc, err);

  rc_close(s);
  if (fflush(stdout) != 0) ++failures;
  if (failures > 0) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  return 0;
}
