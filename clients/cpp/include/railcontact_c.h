/* railcontact_c.h: a plain C interface to a railcontact wheel/rail
 * co-simulation session (the service's WheelRailSession stream), for MBS
 * user-force routines in C, or in Fortran through ISO_C_BINDING.
 *
 * Units are SI. Frames and signs are the service's: the track frame has x
 * forward, y to the right, z down; every force here acts ON THE RAIL (the
 * force on the wheelset is its negative). Patch frame: x along the track,
 * s lateral in the tangent plane towards the field side, n into the rail.
 *
 * Only plain-old-data structs cross this interface, with fixed-size
 * members (double, int32_t, uint64_t) so that Fortran BIND(C) types match
 * them; no C++ exception crosses it.
 *
 * Errors: every function that can fail returns 0 on success, otherwise a
 * gRPC status code (> 0, e.g. 3 INVALID_ARGUMENT, 5 NOT_FOUND, 9
 * FAILED_PRECONDITION, 14 UNAVAILABLE) or RC_ERR_USAGE (-1) for a null
 * pointer or similar misuse, and writes a NUL-terminated description into
 * `err` (at most `errlen` bytes, truncated if longer; `err` may be NULL
 * when errlen is 0). The description is "CODE_NAME: message", followed by
 * " (field PATH)" when the server named the field at fault
 * (e.g. "step.load.vertical_force_n").
 * A refused step or rollback (out of order, invalid input, unknown mark)
 * changes nothing and the session stays usable; rc_is_open() tells whether
 * the stream itself failed (server gone, cancelled), after which every
 * call fails and the session only needs rc_close().
 *
 * Ownership: rc_open() returns a session owned by the caller, released by
 * exactly one rc_close(). Input structs are read during the call only;
 * output structs are caller-owned and overwritten whole on success.
 *
 * Thread-safety: a session must be used by one thread at a time (calls
 * are synchronous and blocking; nothing is locked). Different sessions
 * are independent and may be used from different threads at once, e.g.
 * one session per wheelset, each stepped from its own thread.
 */
#ifndef RAILCONTACT_C_H
#define RAILCONTACT_C_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Usage error (null pointer): returned instead of a gRPC code. */
#define RC_ERR_USAGE (-1)

/* Contact models (WheelRailModel in the proto). */
#define RC_MODEL_EXACT 1
#define RC_MODEL_HERTZ_FASTSIM 2
#define RC_MODEL_CECT 3
#define RC_MODEL_AUTO 4

/* Index of each wheel in rc_wheel_forces.wheels. */
#define RC_LEFT 0
#define RC_RIGHT 1

/* Side of a warning about the wheelset as a whole rather than one wheel
 * (rc_step_warning; the wheels are RC_LEFT and RC_RIGHT). */
#define RC_WHEELSET (-1)

/* Kinds of plausibility warning (WheelRailWarningKind in the proto), see
 * rc_step_warning. */
/* A wheel pressed into its rail far beyond the elastic approach of its
 * load: a prescribed roll that leaves it above its rail (field
 * step.position.roll_rad), else step.load.vertical_force_n. Per wheel. */
#define RC_WARNING_APPROACH 1
/* Both wheels driven or braked the same way to near saturation by a
 * prescribed pitch rate far from free rolling (field
 * step.velocity.pitch_rad_per_s). For the wheelset (side RC_WHEELSET). */
#define RC_WARNING_LONGITUDINAL_FORCE 2
/* The exact solver of some of a wheel's patches stopped at its iteration
 * limit: the wheel's forces include a last iterate (field open.model; the
 * value counts those patches, the limit is 0). Per wheel. */
#define RC_WARNING_UNCONVERGED 3

/* Patches kept per wheel; a wheel with more reports the count in
 * n_patches_total and the first RC_MAX_PATCHES (field side first). Its
 * total force always covers every patch. */
#define RC_MAX_PATCHES 8

/* An opaque session. */
typedef struct rc_session rc_session;

/* The wheelset's state at one step. */
typedef struct rc_wheelset_state {
  /* Lateral shift of the wheelset centre, to the right [m]. */
  double lateral_m;
  /* Yaw angle [rad], |value| <= 0.2; > 0 turns forward to the right. */
  double yaw_rad;
  /* Roll angle [rad], used when has_roll_rad != 0; else found from the
   * profiles so that both wheels touch their rails. */
  double roll_rad;
  /* Forward speed [m/s], > 0. */
  double forward_m_per_s;
  /* Lateral speed [m/s]. */
  double lateral_m_per_s;
  /* Vertical speed (down) [m/s]. */
  double vertical_m_per_s;
  /* Roll rate [rad/s]. */
  double roll_rad_per_s;
  /* Yaw rate [rad/s]. */
  double yaw_rad_per_s;
  /* Rotation rate about the axle [rad/s] (negative rolling forward), used
   * when has_pitch_rad_per_s != 0; else free rolling at the nominal radius. */
  double pitch_rad_per_s;
  /* Vertical force of each wheel on its rail [N], > 0. */
  double vertical_force_n;
  /* Nonzero: roll_rad is given. */
  int32_t has_roll_rad;
  /* Nonzero: pitch_rad_per_s is given. */
  int32_t has_pitch_rad_per_s;
  /* Nonzero: remember the state after this step, for rc_rollback(). */
  int32_t mark;
  /* Unused; set to 0. */
  int32_t reserved;
} rc_wheelset_state;

/* One contact patch. */
typedef struct rc_patch {
  /* Contact angle [rad], > 0 towards flange contact. */
  double contact_angle_rad;
  /* Reference point in the track frame [m]. */
  double track_x_m, track_y_m, track_z_m;
  /* Rolling radius at the reference point [m]. */
  double rolling_radius_m;
  /* Creepages: longitudinal [-], lateral [-], spin [1/m]. */
  double creepage_long, creepage_lat, spin_per_m;
  /* Forces on the rail in the patch frame [N], spin moment [N m]. */
  double normal_force_n, fx_n, fs_n, mz_nm;
  /* Approach [m], largest pressure [Pa], area [m^2], adhesion share [-],
   * frictional power [W]. */
  double approach_m, max_pressure_pa, contact_area_m2, adhesion_fraction;
  double frictional_power_w;
  /* The patch's force on the rail in the track frame (x, y, z) [N]. */
  double force_track_n[3];
  /* The model that solved it (RC_MODEL_*). */
  int32_t method;
  int32_t reserved;
} rc_patch;

/* One wheel. */
typedef struct rc_wheel {
  /* The wheel's total force on the rail in the track frame (x, y, z) [N]. */
  double force_track_n[3];
  /* Vertical approach from the rigid position [m]. */
  double vertical_approach_m;
  /* Smallest vertical gap at the rigid position [m]. */
  double min_gap_m;
  /* Nonzero when this wheel was solved (sessions solve both wheels). */
  int32_t solved;
  /* Patches stored below, and patches the wheel has. */
  int32_t n_patches;
  int32_t n_patches_total;
  /* Iterations of the load iteration. */
  int32_t load_iterations;
  rc_patch patches[RC_MAX_PATCHES];
} rc_wheel;

/* The result of one step. */
typedef struct rc_wheel_forces {
  /* The step's index and time [s], echoed. */
  uint64_t step_index;
  double time_s;
  /* Wheelset centre height (down) [m], roll angle used [rad], rotation
   * rate about the axle used [rad/s]. */
  double center_z_m;
  double roll_rad;
  double pitch_rad_per_s;
  /* The server's solve time of this step [s]. */
  double server_time_s;
  /* wheels[RC_LEFT] and wheels[RC_RIGHT]. */
  rc_wheel wheels[2];
  /* Nonzero when the state after this step was marked. */
  int32_t marked;
  /* Plausibility warnings the server sent with this step (0 for a
   * plausible answer): what no elastic wheel/rail contact gives, each
   * naming the input at fault. The forces are the solver's all the same.
   * Read each with rc_step_warning(session, i, ...), 0 <= i < n_warnings. */
  int32_t n_warnings;
} rc_wheel_forces;

/* Connects to `target` (e.g. "127.0.0.1:50051") and opens a session on the
 * profile pair `pair_id` (a registered id, or "mbench_s1002_uic60") with
 * the contact model `model` (RC_MODEL_*), both wheels. Waits up to 10 s
 * for the connection; a refused or unreachable port fails at once.
 * Returns NULL on failure, with the reason in err. */
rc_session* rc_open(const char* target, const char* pair_id, int model, char* err,
                    size_t errlen);

/* rc_open to a server with TLS or bearer tokens: `tls_ca_file` (NULL or
 * "": plaintext) names a PEM file of the authorities to trust and turns
 * TLS on; `token` (NULL or "": none) is sent as `authorization: Bearer
 * TOKEN`. */
rc_session* rc_open_secure(const char* target, const char* pair_id, int model,
                           const char* tls_ca_file, const char* token, char* err,
                           size_t errlen);

/* Solves step `step_index` (0 for the first, then consecutive; after
 * rc_rollback to k, k + 1) at time `time_s` for the wheelset state `in`,
 * and writes the result to `out`. Returns 0 or an error (see above); on
 * error `out` is left unchanged. */
int rc_step(rc_session* session, uint64_t step_index, double time_s,
            const rc_wheelset_state* in, rc_wheel_forces* out, char* err, size_t errlen);

/* Reads warning `index` (0 <= index < n_warnings of the last rc_wheel_forces
 * rc_step wrote) of the session's last successful step. They are kept
 * until the next successful rc_step: a refused step and rc_rollback leave
 * them as they are; before the first step there are none.
 *   kind:    RC_WARNING_APPROACH or RC_WARNING_LONGITUDINAL_FORCE (another
 *            positive value: a kind of a newer server).
 *   side:    RC_LEFT or RC_RIGHT for the wheel concerned, RC_WHEELSET for
 *            the wheelset as a whole.
 *   value:   the measure that exceeded its limit [-]: the wheel's approach
 *            over the elastic approach of its load (APPROACH), the wheels'
 *            total longitudinal force over the adhesion their lateral
 *            forces leave (LONGITUDINAL_FORCE).
 *   limit:   its limit [-]: 10 (APPROACH), 0.9 (LONGITUDINAL_FORCE).
 *   message: the server's text, with its numbers, the input at fault (e.g.
 *            "velocity.pitch_rad_per_s") and what to do; copied NUL-terminated
 *            into at most `message_len` bytes, truncated if longer (never
 *            within a UTF-8 character). The messages run to about 800 bytes:
 *            1024 holds them.
 * Each output pointer may be NULL when not wanted (`message` when
 * message_len is 0). Returns 0, or RC_ERR_USAGE for a NULL session or an
 * index outside [0, n_warnings), outputs then unchanged. */
int rc_step_warning(const rc_session* session, int32_t index, int32_t* kind, int32_t* side,
                    double* value, double* limit, char* message, size_t message_len,
                    char* err, size_t errlen);

/* Returns to the state after the marked step `to_step_index` (marks after
 * it are dropped). On success writes the index the next step must have
 * (to_step_index + 1) to *next_step_index, when that is not NULL. */
int rc_rollback(rc_session* session, uint64_t to_step_index, uint64_t* next_step_index,
                char* err, size_t errlen);

/* The index the next step must have. */
uint64_t rc_next_step_index(const rc_session* session);

/* Nonzero while the stream is usable (not failed, not closed). */
int rc_is_open(const rc_session* session);

/* Ends the stream and frees the session. NULL is accepted. */
void rc_close(rc_session* session);

#ifdef __cplusplus
}
#endif

#endif /* RAILCONTACT_C_H */
