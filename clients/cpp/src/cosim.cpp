// railcontact::CoSimSession over the synchronous gRPC C++ API.
#include "railcontact/cosim.hpp"

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

#include "railcontact/v1/railcontact.grpc.pb.h"

namespace pb = railcontact::v1;

namespace railcontact {

namespace {

const char* code_name(int code) {
  static const char* const names[] = {
      "OK",                 "CANCELLED",         "UNKNOWN",        "INVALID_ARGUMENT",
      "DEADLINE_EXCEEDED",  "NOT_FOUND",         "ALREADY_EXISTS", "PERMISSION_DENIED",
      "RESOURCE_EXHAUSTED", "FAILED_PRECONDITION", "ABORTED",      "OUT_OF_RANGE",
      "UNIMPLEMENTED",      "INTERNAL",          "UNAVAILABLE",    "DATA_LOSS",
      "UNAUTHENTICATED"};
  if (code >= 0 && code < static_cast<int>(sizeof(names) / sizeof(names[0]))) {
    return names[code];
  }
  return "UNKNOWN";
}

std::string describe(int code, const std::string& message, const std::string& field) {
  std::string s = code_name(code);
  s += ": ";
  s += message;
  if (!field.empty()) {
    s += " (field ";
    s += field;
    s += ")";
  }
  return s;
}

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", s);
  return buf;
}

TrackForce track_force(const pb::TrackForce& f) { return TrackForce{f.x_n(), f.y_n(), f.z_n()}; }

PatchSummary patch_summary(const pb::WheelRailPatch& p) {
  PatchSummary s;
  s.method = static_cast<Model>(p.method());
  s.contact_angle_rad = p.contact_angle_rad();
  s.track_x_m = p.track_x_m();
  s.track_y_m = p.track_y_m();
  s.track_z_m = p.track_z_m();
  s.rolling_radius_m = p.rolling_radius_m();
  s.creepage_long = p.creepage_long();
  s.creepage_lat = p.creepage_lat();
  s.spin_per_m = p.spin_per_m();
  s.normal_force_n = p.normal_force_n();
  s.fx_n = p.fx_n();
  s.fs_n = p.fs_n();
  s.mz_nm = p.mz_nm();
  s.approach_m = p.approach_m();
  s.max_pressure_pa = p.max_pressure_pa();
  s.contact_area_m2 = p.contact_area_m2();
  s.adhesion_fraction = p.adhesion_fraction();
  s.frictional_power_w = p.frictional_power_w();
  s.force_track_n = track_force(p.force_track_n());
  return s;
}

StepOutput step_output(const pb::WheelRailSessionStepResult& r) {
  StepOutput out;
  out.step_index = r.step_index();
  out.time_s = r.time_s();
  out.marked = r.marked();
  const pb::WheelRailResult& res = r.result();
  out.center_z_m = res.center_z_m();
  out.roll_rad = res.roll_rad();
  out.pitch_rad_per_s = res.pitch_rad_per_s();
  out.server_time_s = res.timing().search_s() + res.timing().geometry_s() + res.timing().solve_s();
  out.wheels.reserve(static_cast<std::size_t>(res.wheels_size()));
  for (const pb::WheelRailWheel& w : res.wheels()) {
    WheelResult wr;
    wr.side = static_cast<Side>(w.side());
    wr.force_track_n = track_force(w.force_track_n());
    wr.vertical_approach_m = w.vertical_approach_m();
    wr.min_gap_m = w.min_gap_m();
    wr.load_iterations = w.load_iterations();
    wr.patches.reserve(static_cast<std::size_t>(w.patches_size()));
    for (const pb::WheelRailPatch& p : w.patches()) {
      wr.patches.push_back(patch_summary(p));
    }
    out.wheels.push_back(std::move(wr));
  }
  out.warnings.reserve(static_cast<std::size_t>(res.warnings_size()));
  for (const pb::WheelRailWarning& w : res.warnings()) {
    Warning warning;
    warning.kind = static_cast<WarningKind>(w.kind());
    warning.field = w.field();
    if (w.side() != pb::WHEEL_SIDE_UNSPECIFIED) {
      warning.side = static_cast<Side>(w.side());
    }
    warning.value = w.value();
    warning.limit = w.limit();
    warning.message = w.message();
    out.warnings.push_back(std::move(warning));
  }
  return out;
}

}  // namespace

Error::Error(int code, std::string message, std::string field, bool session_closed)
    : std::runtime_error(describe(code, message, field)),
      code_(code),
      message_(std::move(message)),
      field_(std::move(field)),
      session_closed_(session_closed) {}

struct CoSimSession::Impl {
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<pb::ContactService::Stub> stub;
  grpc::ClientContext context;
  std::unique_ptr<grpc::ClientReaderWriter<pb::WheelRailSessionRequest, pb::WheelRailSessionResponse>>
      stream;
  bool open = false;
  std::uint64_t next_step = 0;
  std::string session_id;
  std::string pair_id;
  Model model = Model::Exact;

  // The stream is gone: collect the server's status and throw it.
  [[noreturn]] void fail_stream(const char* what) {
    open = false;
    grpc::Status status = stream->Finish();
    if (status.ok()) {
      throw Error(grpc::StatusCode::INTERNAL,
                  std::string("the server ended the session stream ") + what, "", true);
    }
    throw Error(status.error_code(), status.error_message(), "", true);
  }

  // Half-closes the stream, drops what the server still sends and returns
  // its final status.
  grpc::Status finish() {
    open = false;
    stream->WritesDone();
    pb::WheelRailSessionResponse extra;
    while (stream->Read(&extra)) {
    }
    return stream->Finish();
  }

  void ensure_open() const {
    if (!open) {
      throw Error(grpc::StatusCode::FAILED_PRECONDITION, "the session is closed", "", true);
    }
  }

  // Sends one request and reads its one answer.
  pb::WheelRailSessionResponse exchange(const pb::WheelRailSessionRequest& request) {
    ensure_open();
    if (!stream->Write(request)) {
      fail_stream("while sending");
    }
    pb::WheelRailSessionResponse response;
    if (!stream->Read(&response)) {
      fail_stream("without an answer");
    }
    if (response.kind_case() == pb::WheelRailSessionResponse::kError) {
      const pb::ItemError& e = response.error();
      throw Error(e.code(), e.message(), e.field(), false);
    }
    return response;
  }
};

CoSimSession::CoSimSession(const SessionOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (options.tls || !options.tls_ca_file.empty()) {
    grpc::SslCredentialsOptions ssl;
    if (!options.tls_ca_file.empty()) {
      std::ifstream file(options.tls_ca_file, std::ios::binary);
      if (!file) {
        throw Error(grpc::StatusCode::INVALID_ARGUMENT,
                    "cannot read the TLS authorities file " + options.tls_ca_file, "tls_ca_file",
                    true);
      }
      std::ostringstream pem;
      pem << file.rdbuf();
      ssl.pem_root_certs = pem.str();
    }
    credentials = grpc::SslCredentials(ssl);
  }
  s.channel = grpc::CreateChannel(options.target, credentials);
  const auto deadline =
      std::chrono::system_clock::now() +
      std::chrono::microseconds(static_cast<std::int64_t>(options.connect_timeout_s * 1e6));
  // Wait for READY, but give up at the first failure (a refused or
  // unreachable port fails at once instead of retrying until the deadline).
  for (;;) {
    const grpc_connectivity_state state = s.channel->GetState(true);
    if (state == GRPC_CHANNEL_READY) break;
    if (state == GRPC_CHANNEL_TRANSIENT_FAILURE || state == GRPC_CHANNEL_SHUTDOWN) {
      throw Error(grpc::StatusCode::UNAVAILABLE,
                  "could not connect to " + options.target +
                      ": refused or unreachable (is the server running there?)",
                  "", true);
    }
    if (!s.channel->WaitForStateChange(state, deadline)) {
      throw Error(grpc::StatusCode::UNAVAILABLE,
                  "could not connect to " + options.target + " within " +
                      seconds(options.connect_timeout_s),
                  "", true);
    }
  }
  s.stub = pb::ContactService::NewStub(s.channel);
  if (!options.token.empty()) {
    s.context.AddMetadata("authorization", "Bearer " + options.token);
  }
  s.stream = s.stub->WheelRailSession(&s.context);
  s.open = true;

  pb::WheelRailSessionRequest request;
  pb::WheelRailSessionOpen* open = request.mutable_open();
  open->set_pair_id(options.pair_id);
  open->set_model(static_cast<pb::WheelRailModel>(options.model));
  open->set_sides(static_cast<pb::WheelSides>(options.sides));
  if (options.element_size_m) {
    open->set_element_size_m(*options.element_size_m);
  }
  open->set_client_label(options.client_label);
  pb::WheelRailSessionResponse response;
  try {
    response = s.exchange(request);
  } catch (const Error& e) {
    // A refused open leaves no session behind, whatever the server says.
    if (s.open) {
      s.finish();
    }
    throw Error(e.code(), e.message(), e.field(), true);
  }
  if (response.kind_case() != pb::WheelRailSessionResponse::kOpened) {
    s.context.TryCancel();
    s.open = false;
    s.stream->Finish();
    throw Error(grpc::StatusCode::INTERNAL, "the server answered the open with another message",
                "", true);
  }
  s.session_id = response.opened().session_id();
  s.pair_id = response.opened().pair_id();
  s.model = static_cast<Model>(response.opened().model());
}

CoSimSession::~CoSimSession() {
  if (impl_) {
    try {
      close();
    } catch (...) {
      // A destructor reports nothing; call close() to see the status.
    }
  }
}

CoSimSession::CoSimSession(CoSimSession&&) noexcept = default;
CoSimSession& CoSimSession::operator=(CoSimSession&& other) noexcept {
  if (this != &other) {
    if (impl_) {
      try {
        close();
      } catch (...) {
      }
    }
    impl_ = std::move(other.impl_);
  }
  return *this;
}

StepOutput CoSimSession::step(std::uint64_t step_index, double time_s, const WheelsetState& state,
                              bool mark) {
  if (!impl_) {
    throw Error(grpc::StatusCode::FAILED_PRECONDITION, "the session was moved from", "", true);
  }
  pb::WheelRailSessionRequest request;
  pb::WheelRailSessionStep* st = request.mutable_step();
  st->set_step_index(step_index);
  st->set_time_s(time_s);
  st->set_mark(mark);
  pb::WheelsetPosition* pos = st->mutable_position();
  pos->set_lateral_m(state.lateral_m);
  pos->set_yaw_rad(state.yaw_rad);
  if (state.roll_rad) {
    pos->set_roll_rad(*state.roll_rad);
  }
  pb::WheelsetVelocity* vel = st->mutable_velocity();
  vel->set_forward_m_per_s(state.forward_m_per_s);
  vel->set_lateral_m_per_s(state.lateral_m_per_s);
  vel->set_vertical_m_per_s(state.vertical_m_per_s);
  vel->set_roll_rad_per_s(state.roll_rad_per_s);
  vel->set_yaw_rad_per_s(state.yaw_rad_per_s);
  if (state.pitch_rad_per_s) {
    vel->set_pitch_rad_per_s(*state.pitch_rad_per_s);
  }
  st->mutable_load()->set_vertical_force_n(state.vertical_force_n);

  pb::WheelRailSessionResponse response = impl_->exchange(request);
  if (response.kind_case() != pb::WheelRailSessionResponse::kStep ||
      response.step().step_index() != step_index) {
    throw Error(grpc::StatusCode::INTERNAL,
                "the server answered step " + std::to_string(step_index) +
                    " with another message",
                "", false);
  }
  impl_->next_step = step_index + 1;
  return step_output(response.step());
}

std::uint64_t CoSimSession::rollback(std::uint64_t to_step_index) {
  if (!impl_) {
    throw Error(grpc::StatusCode::FAILED_PRECONDITION, "the session was moved from", "", true);
  }
  pb::WheelRailSessionRequest request;
  request.mutable_rollback()->set_to_step_index(to_step_index);
  pb::WheelRailSessionResponse response = impl_->exchange(request);
  if (response.kind_case() != pb::WheelRailSessionResponse::kRolledBack) {
    throw Error(grpc::StatusCode::INTERNAL, "the server answered a rollback with another message",
                "", false);
  }
  impl_->next_step = response.rolled_back().next_step_index();
  return impl_->next_step;
}

std::uint64_t CoSimSession::next_step_index() const noexcept {
  return impl_ ? impl_->next_step : 0;
}

const std::string& CoSimSession::session_id() const noexcept { return impl_->session_id; }
const std::string& CoSimSession::pair_id() const noexcept { return impl_->pair_id; }
Model CoSimSession::model() const noexcept { return impl_->model; }

bool CoSimSession::is_open() const noexcept { return impl_ && impl_->open; }

void CoSimSession::close() {
  if (!impl_ || !impl_->open) {
    return;
  }
  grpc::Status status = impl_->finish();
  if (!status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) {
    throw Error(status.error_code(), status.error_message(), "", true);
  }
}

}  // namespace railcontact
