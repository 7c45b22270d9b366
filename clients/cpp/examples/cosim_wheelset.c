/* cosim_wheelset: a wheelset's lateral dynamics co-simulated with the
 * railcontact service through the C interface (railcontact_c.h), as an MBS
 * user-force routine would do it.
 *
 * The wheelset (mass 1500 kg) is tied laterally to a fixed frame by a
 * spring and runs at 30 m/s on the pair's track, starting 3 mm to the
 * right at rest. Each step sends its lateral position and speed, gets the
 * wheel/rail forces and integrates m y'' = F_contact + F_spring with
 * semi-implicit Euler (fixed step 1 ms). The force on the wheelset is the
 * negative of the forces on the rails that the service returns.
 *
 * One mark/rollback round: the step MARK is marked; after REPLAY further
 * steps the session rolls back to it, the integrator state goes back too,
 * and the same steps are solved again: their forces must be bit-identical.
 * A step with a wrong index must be refused in-band with the session
 * staying usable.
 *
 * The server's plausibility warnings (rc_step_warning) are printed on
 * stderr, each once per step ("step K: warning: ..."; the steps solved
 * again after the rollback are not printed again). The wheelset rotates
 * at the server's default, -V / nominal radius, unless --pitch-rad-per-s
 * prescribes its rotation rate [rad/s]: one far from free rolling (e.g.
 * -68.5 rad/s, 5 % faster than -V / 0.46 m) drives both wheels to
 * saturation, which the server warns about at every step.
 *
 * Usage: cosim_wheelset TARGET [--model hertz_fastsim|exact|cect|auto]
 *                              [--pair PAIR_ID] [--steps N]
 *                              [--pitch-rad-per-s RATE] [--tls-ca FILE.pem]
 * Prints a CSV on stdout: step, time_s, lateral_m, lateral_m_per_s,
 * contact_force_y_n (on the wheelset, track y to the right),
 * spring_force_y_n. Exits 1 on any error, 2 on bad usage. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "railcontact_c.h"

#define MASS_KG 1500.0
#define SPRING_N_PER_M 2.0e6
#define SPEED_M_PER_S 30.0
#define WHEEL_LOAD_N 60.0e3
#define INITIAL_LATERAL_M 3.0e-3
#define STEP_S 1.0e-3
#define MARK 100
#define REPLAY 10
#define FAILED_PRECONDITION 9

static int model_of(const char* name) {
  if (strcmp(name, "exact") == 0) return RC_MODEL_EXACT;
  if (strcmp(name, "hertz_fastsim") == 0) return RC_MODEL_HERTZ_FASTSIM;
  if (strcmp(name, "cect") == 0) return RC_MODEL_CECT;
  if (strcmp(name, "auto") == 0) return RC_MODEL_AUTO;
  return 0;
}

static int usage(const char* argv0) {
  fprintf(stderr,
          "usage: %s TARGET [--model hertz_fastsim|exact|cect|auto] [--pair PAIR_ID] "
          "[--steps N] [--pitch-rad-per-s RATE] [--tls-ca FILE.pem]\n"
          "(a bearer token, if the server needs one, from RAILCONTACT_TOKEN)\n",
          argv0);
  return 2;
}

static const char* warning_kind_name(int32_t kind) {
  switch (kind) {
    case RC_WARNING_APPROACH:
      return "approach";
    case RC_WARNING_LONGITUDINAL_FORCE:
      return "longitudinal_force";
    case RC_WARNING_UNCONVERGED:
      return "unconverged";
    default:
      return "unknown kind";
  }
}

static const char* side_name(int32_t side) {
  switch (side) {
    case RC_LEFT:
      return "left wheel";
    case RC_RIGHT:
      return "right wheel";
    default:
      return "wheelset";
  }
}

/* Prints the plausibility warnings of step k (just solved) on stderr;
 * returns nonzero when one cannot be read. */
static int print_warnings(rc_session* s, long k, const rc_wheel_forces* f) {
  char message[1024], err[256];
  for (int32_t i = 0; i < f->n_warnings; ++i) {
    int32_t kind = 0, side = 0;
    double value = 0.0, limit = 0.0;
    if (rc_step_warning(s, i, &kind, &side, &value, &limit, message, sizeof message, err,
                        sizeof err) != 0) {
      fprintf(stderr, "rc_step_warning %ld/%d: %s\n", k, (int)i, err);
      return 1;
    }
    fprintf(stderr, "step %ld: warning: %s (%s), measure %.5g, limit %.4g: %s\n", k,
            warning_kind_name(kind), side_name(side), value, limit, message);
  }
  return 0;
}

/* The lateral contact force on the wheelset [N]: minus the rails' forces. */
static double contact_force_y(const rc_wheel_forces* f) {
  return -(f->wheels[RC_LEFT].force_track_n[1] + f->wheels[RC_RIGHT].force_track_n[1]);
}

int main(int argc, char** argv) {
  const char* target = NULL;
  const char* pair = "mbench_s1002_uic60";
  int model = RC_MODEL_HERTZ_FASTSIM;
  long steps = 200;
  const char* tls_ca = NULL;
  double pitch = 0.0;
  int has_pitch = 0;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--model") == 0 && i + 1 < argc) {
      model = model_of(argv[++i]);
      if (model == 0) return usage(argv[0]);
    } else if (strcmp(argv[i], "--tls-ca") == 0 && i + 1 < argc) {
      tls_ca = argv[++i];
    } else if (strcmp(argv[i], "--pitch-rad-per-s") == 0 && i + 1 < argc) {
      char* end = NULL;
      pitch = strtod(argv[++i], &end);
      if (end == argv[i] || *end != '\0' || !isfinite(pitch)) return usage(argv[0]);
      has_pitch = 1;
    } else if (strcmp(argv[i], "--pair") == 0 && i + 1 < argc) {
      pair = argv[++i];
    } else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
      steps = strtol(argv[++i], NULL, 10);
      if (steps < MARK + REPLAY + 1) {
        fprintf(stderr, "--steps must be at least %d\n", MARK + REPLAY + 1);
        return 2;
      }
    } else if (target == NULL && argv[i][0] != '-') {
      target = argv[i];
    } else {
      return usage(argv[0]);
    }
  }
  if (target == NULL) return usage(argv[0]);

  char err[1024];
  rc_session* s = rc_open_secure(target, pair, model, tls_ca, getenv("RAILCONTACT_TOKEN"), err,
                                 sizeof err);
  if (s == NULL) {
    fprintf(stderr, "rc_open: %s\n", err);
    return 1;
  }

  rc_wheelset_state in;
  memset(&in, 0, sizeof in);
  in.forward_m_per_s = SPEED_M_PER_S;
  in.vertical_force_n = WHEEL_LOAD_N;
  in.has_pitch_rad_per_s = has_pitch;
  in.pitch_rad_per_s = pitch;

  rc_wheel_forces out;
  rc_wheel_forces first_pass[REPLAY];
  double y = INITIAL_LATERAL_M, v = 0.0;
  double y_mark = 0.0, v_mark = 0.0;
  int replaying = 0, replayed = 0, status = 0;

  printf("step,time_s,lateral_m,lateral_m_per_s,contact_force_y_n,spring_force_y_n\n");
  for (long k = 0; k < steps; ++k) {
    const double t = (double)k * STEP_S;
    in.lateral_m = y;
    in.lateral_m_per_s = v;
    in.mark = (k == MARK && !replayed) ? 1 : 0;
    int rc = rc_step(s, (uint64_t)k, t, &in, &out, err, sizeof err);
    if (rc != 0) {
      fprintf(stderr, "rc_step %ld: %s\n", k, err);
      status = 1;
      break;
    }
    if (in.mark && !out.marked) {
      fprintf(stderr, "step %ld: asked to mark, the server did not\n", k);
      status = 1;
      break;
    }
    if (!replaying && print_warnings(s, k, &out) != 0) {
      status = 1;
      break;
    }
    const double fc = contact_force_y(&out);
    const double fs = -SPRING_N_PER_M * y;
    if (!isfinite(fc)) {
      fprintf(stderr, "step %ld: contact force is not finite\n", k);
      status = 1;
      break;
    }
    if (k > MARK && k <= MARK + REPLAY) {
      rc_wheel_forces* saved = &first_pass[k - MARK - 1];
      if (!replaying) {
        *saved = out;
      } else if (memcmp(saved->wheels, out.wheels, sizeof out.wheels) != 0 ||
                 saved->n_warnings != out.n_warnings ||
                 memcmp(&saved->center_z_m, &out.center_z_m, sizeof out.center_z_m) != 0 ||
                 memcmp(&saved->roll_rad, &out.roll_rad, sizeof out.roll_rad) != 0) {
        fprintf(stderr, "step %ld after rollback: forces differ from the first pass\n", k);
        status = 1;
        break;
      }
    }
    if (!replaying) {
      printf("%ld,%.6f,%.17g,%.17g,%.17g,%.17g\n", k, t, y, v, fc, fs);
    }

    /* Semi-implicit Euler: the force at step k moves the state to k + 1. */
    v += STEP_S * (fc + fs) / MASS_KG;
    y += STEP_S * v;

    if (k == MARK && !replayed) {
      y_mark = y;
      v_mark = v;
    }
    if (k == MARK + REPLAY && !replayed && !replaying) {
      /* A refused step: wrong index, answered in-band, nothing changes. */
      rc = rc_step(s, (uint64_t)(k + 5), t, &in, &out, err, sizeof err);
      if (rc != FAILED_PRECONDITION || !rc_is_open(s)) {
        fprintf(stderr, "out-of-order step: expected FAILED_PRECONDITION, got %d (%s)\n", rc,
                err);
        status = 1;
        break;
      }
      fprintf(stderr, "out-of-order step refused as expected: %s\n", err);
      uint64_t next = 0;
      rc = rc_rollback(s, MARK, &next, err, sizeof err);
      if (rc != 0 || next != MARK + 1) {
        fprintf(stderr, "rc_rollback: %s (next step %llu)\n", rc != 0 ? err : "wrong next step",
                (unsigned long long)next);
        status = 1;
        break;
      }
      y = y_mark;
      v = v_mark;
      k = MARK; /* the loop's ++k makes it MARK + 1 */
      replaying = 1;
    } else if (replaying && k == MARK + REPLAY) {
      replaying = 0;
      replayed = 1;
      fprintf(stderr, "rollback to step %d: %d steps solved again, forces bit-identical\n", MARK,
              REPLAY);
    }
  }
  if (status == 0 && !replayed) {
    fprintf(stderr, "the rollback round did not run\n");
    status = 1;
  }
  rc_close(s);
  if (fflush(stdout) != 0) status = 1;
  return status;
}
