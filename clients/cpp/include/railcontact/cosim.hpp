// railcontact::CoSimSession: a wheel/rail co-simulation session over the
// railcontact gRPC service's WheelRailSession stream.
//
// Units are SI. Frames and signs are the service's (see
// proto/railcontact/v1/railcontact.proto): the track frame has x forward,
// y to the right, z down; forces are those acting ON THE RAIL (the force
// on the wheelset is their negative).
//
// Thread-safety: one session is one gRPC stream and must be used by one
// thread at a time (calls are synchronous and do not lock). Different
// sessions are independent and may be used from different threads at the
// same time.
#ifndef RAILCONTACT_COSIM_HPP
#define RAILCONTACT_COSIM_HPP

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace railcontact {

// Contact model of each patch (WheelRailModel in the proto).
enum class Model : int {
  Exact = 1,
  HertzFastsim = 2,
  Cect = 3,
  Auto = 4,
};

// Which wheels a session solves (WheelSides in the proto).
enum class Sides : int {
  Both = 1,
  Left = 2,
  Right = 3,
};

// One wheel (WheelSide in the proto).
enum class Side : int {
  Left = 1,
  Right = 2,
};

// What a plausibility warning finds (WheelRailWarningKind in the proto).
// Another value: a kind of a newer server.
enum class WarningKind : int {
  // A wheel pressed into its rail far beyond the elastic approach of its
  // load: a prescribed roll that leaves it above its rail (field
  // step.position.roll_rad), else step.load.vertical_force_n. Per wheel.
  Approach = 1,
  // Both wheels driven or braked the same way to near saturation by a
  // prescribed pitch rate far from free rolling (field
  // step.velocity.pitch_rad_per_s). For the wheelset as a whole.
  LongitudinalForce = 2,
};

// An error: a refused step or rollback (the session stays open) or a
// failed stream (the session is closed). `code()` is the gRPC status
// code, `message()` the server's text, `field()` the path of the field at
// fault in the request (empty when the server named none or the whole
// stream failed).
class Error : public std::runtime_error {
 public:
  Error(int code, std::string message, std::string field, bool session_closed);
  int code() const noexcept { return code_; }
  const std::string& message() const noexcept { return message_; }
  const std::string& field() const noexcept { return field_; }
  // True when the stream is gone and the session can take no more calls.
  bool session_closed() const noexcept { return session_closed_; }

 private:
  int code_;
  std::string message_;
  std::string field_;
  bool session_closed_;
};

// The wheelset's state at one step: position relative to the track,
// velocity and the vertical load of each wheel.
struct WheelsetState {
  // Lateral shift of the wheelset centre, to the right [m].
  double lateral_m = 0.0;
  // Yaw angle [rad], |value| <= 0.2.
  double yaw_rad = 0.0;
  // Roll angle [rad]; not set: found so that both wheels touch.
  std::optional<double> roll_rad;
  // Forward speed [m/s], > 0.
  double forward_m_per_s = 0.0;
  // Lateral speed [m/s].
  double lateral_m_per_s = 0.0;
  // Vertical speed (down) [m/s].
  double vertical_m_per_s = 0.0;
  // Roll rate [rad/s].
  double roll_rad_per_s = 0.0;
  // Yaw rate [rad/s].
  double yaw_rad_per_s = 0.0;
  // Rotation rate about the axle [rad/s]; not set: free rolling.
  std::optional<double> pitch_rad_per_s;
  // Vertical force of each wheel on its rail [N], > 0.
  double vertical_force_n = 0.0;
};

// A force in the track frame (x forward, y right, z down) [N].
struct TrackForce {
  double x_n = 0.0;
  double y_n = 0.0;
  double z_n = 0.0;
};

// The summary of one contact patch (WheelRailPatch without grids).
struct PatchSummary {
  Model method = Model::Exact;
  double contact_angle_rad = 0.0;
  // Reference point in the track frame [m].
  double track_x_m = 0.0;
  double track_y_m = 0.0;
  double track_z_m = 0.0;
  double rolling_radius_m = 0.0;
  double creepage_long = 0.0;
  double creepage_lat = 0.0;
  double spin_per_m = 0.0;
  // Forces on the rail in the patch frame [N] and spin moment [N m].
  double normal_force_n = 0.0;
  double fx_n = 0.0;
  double fs_n = 0.0;
  double mz_nm = 0.0;
  double approach_m = 0.0;
  double max_pressure_pa = 0.0;
  double contact_area_m2 = 0.0;
  double adhesion_fraction = 0.0;
  double frictional_power_w = 0.0;
  // The patch's force on the rail in the track frame [N].
  TrackForce force_track_n;
};

// One wheel's result.
struct WheelResult {
  Side side = Side::Left;
  // The wheel's total force on the rail in the track frame [N].
  TrackForce force_track_n;
  double vertical_approach_m = 0.0;
  double min_gap_m = 0.0;
  std::uint32_t load_iterations = 0;
  // Patches from the field side to the gauge side.
  std::vector<PatchSummary> patches;
};

// A plausibility warning (WheelRailWarning in the proto): what in the
// answer no elastic wheel/rail contact gives, naming the input at fault.
// The answer is the solver's all the same: a warning is not an error.
struct Warning {
  WarningKind kind = WarningKind::Approach;
  // Path of the input at fault in the step request, e.g.
  // "step.velocity.pitch_rad_per_s".
  std::string field;
  // The wheel concerned; not set: the wheelset as a whole.
  std::optional<Side> side;
  // The measure that exceeded its limit [-]: the wheel's approach over the
  // elastic approach of its load (Approach), the wheels' total longitudinal
  // force over the adhesion their lateral forces leave (LongitudinalForce).
  double value = 0.0;
  // Its limit [-]: 10 (Approach), 0.9 (LongitudinalForce).
  double limit = 0.0;
  // What was found, with its numbers, why, and what to do.
  std::string message;
};

// The answer to one step.
struct StepOutput {
  std::uint64_t step_index = 0;
  double time_s = 0.0;
  bool marked = false;
  // Wheelset centre height (down) [m], roll angle used [rad] and rotation
  // rate about the axle used [rad/s].
  double center_z_m = 0.0;
  double roll_rad = 0.0;
  double pitch_rad_per_s = 0.0;
  // The wheels solved, left first.
  std::vector<WheelResult> wheels;
  // The server's solve time of this step [s] (search + geometry + solve).
  double server_time_s = 0.0;
  // Plausibility warnings; empty for a plausible answer.
  std::vector<Warning> warnings;
};

// Settings of a session.
struct SessionOptions {
  // gRPC target, e.g. "127.0.0.1:50051" or "dns:///host:port".
  std::string target;
  // A registered pair's id or a built-in pair's name.
  std::string pair_id = "mbench_s1002_uic60";
  Model model = Model::HertzFastsim;
  Sides sides = Sides::Both;
  // Element size of the patch grids [m]; not set: the pair's.
  std::optional<double> element_size_m;
  // A label for the server's logs.
  std::string client_label = "railcontact-cpp";
  // How long to wait for the connection at open [s].
  double connect_timeout_s = 10.0;
  // TLS: connect with TLS when set. `tls_ca_file` names a PEM file of the
  // authorities to trust (empty with `tls`: gRPC's default roots).
  bool tls = false;
  std::string tls_ca_file;
  // Bearer token sent as `authorization: Bearer TOKEN` (servers with
  // auth_tokens_file); empty: none.
  std::string token;
};

// A wheel/rail co-simulation session: one WheelRailSession stream. The
// constructor connects and opens the session (throws Error when the server
// is unreachable or refuses, e.g. NOT_FOUND for an unknown pair). Steps
// must come in order: 0, 1, 2, ...; after rollback(k) the next is k + 1.
// The destructor closes the stream.
class CoSimSession {
 public:
  explicit CoSimSession(const SessionOptions& options);
  ~CoSimSession();
  CoSimSession(const CoSimSession&) = delete;
  CoSimSession& operator=(const CoSimSession&) = delete;
  CoSimSession(CoSimSession&&) noexcept;
  CoSimSession& operator=(CoSimSession&&) noexcept;

  // Solves one step. With `mark`, the server remembers the state after it
  // so that rollback(step_index) can return to it. A refused step throws
  // Error with session_closed() false and changes nothing.
  StepOutput step(std::uint64_t step_index, double time_s, const WheelsetState& state,
                  bool mark = false);

  // Returns to the state after a marked step (marks after it are dropped);
  // returns the index the next step must have.
  std::uint64_t rollback(std::uint64_t to_step_index);

  // The index the next step must have (as far as this client knows).
  std::uint64_t next_step_index() const noexcept;

  // Server-assigned session id, pair id (a built-in name resolved) and
  // the model that runs.
  const std::string& session_id() const noexcept;
  const std::string& pair_id() const noexcept;
  Model model() const noexcept;

  // Ends the stream and waits for the server's status (idempotent).
  // Throws Error if the server ended the stream with an error.
  void close();
  bool is_open() const noexcept;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace railcontact

#endif  // RAILCONTACT_COSIM_HPP
