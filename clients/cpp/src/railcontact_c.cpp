// The C interface (railcontact_c.h) over railcontact::CoSimSession: every
// exception is caught here and turned into a return code and a message.
#include "railcontact_c.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "railcontact/cosim.hpp"

struct rc_session {
  railcontact::CoSimSession session;
  // The warnings of the last successful step (rc_step_warning).
  std::vector<railcontact::Warning> warnings;
  explicit rc_session(const railcontact::SessionOptions& options) : session(options) {}
};

namespace {

constexpr int kInternal = 13;
constexpr int kResourceExhausted = 8;

// Copies `text` NUL-terminated into `dst` (at most `len` bytes), cut short
// where it does not fit, before a UTF-8 character rather than within it.
void copy_text(char* dst, std::size_t len, const std::string& text) {
  if (dst == nullptr || len == 0) {
    return;
  }
  std::size_t n = text.size();
  if (n > len - 1) {
    n = len - 1;
    // Back off the continuation bytes (10xxxxxx) of a cut character.
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) {
      --n;
    }
  }
  std::memcpy(dst, text.data(), n);
  dst[n] = '\0';
}

void write_err(char* err, std::size_t errlen, const std::string& text) {
  copy_text(err, errlen, text);
}

void clear_err(char* err, std::size_t errlen) {
  if (err != nullptr && errlen > 0) {
    err[0] = '\0';
  }
}

// Runs `body`, turning exceptions into a code and a message.
template <typename F>
int guarded(char* err, std::size_t errlen, F&& body) {
  try {
    body();
    clear_err(err, errlen);
    return 0;
  } catch (const railcontact::Error& e) {
    write_err(err, errlen, e.what());
    return e.code() > 0 ? e.code() : kInternal;
  } catch (const std::bad_alloc&) {
    write_err(err, errlen, "RESOURCE_EXHAUSTED: out of memory");
    return kResourceExhausted;
  } catch (const std::exception& e) {
    write_err(err, errlen, std::string("INTERNAL: ") + e.what());
    return kInternal;
  } catch (...) {
    write_err(err, errlen, "INTERNAL: unknown C++ exception");
    return kInternal;
  }
}

int usage(char* err, std::size_t errlen, const char* what) {
  write_err(err, errlen, std::string("usage: ") + what);
  return RC_ERR_USAGE;
}

void copy3(double dst[3], const railcontact::TrackForce& f) {
  dst[0] = f.x_n;
  dst[1] = f.y_n;
  dst[2] = f.z_n;
}

void fill_patch(rc_patch& d, const railcontact::PatchSummary& p) {
  d.contact_angle_rad = p.contact_angle_rad;
  d.track_x_m = p.track_x_m;
  d.track_y_m = p.track_y_m;
  d.track_z_m = p.track_z_m;
  d.rolling_radius_m = p.rolling_radius_m;
  d.creepage_long = p.creepage_long;
  d.creepage_lat = p.creepage_lat;
  d.spin_per_m = p.spin_per_m;
  d.normal_force_n = p.normal_force_n;
  d.fx_n = p.fx_n;
  d.fs_n = p.fs_n;
  d.mz_nm = p.mz_nm;
  d.approach_m = p.approach_m;
  d.max_pressure_pa = p.max_pressure_pa;
  d.contact_area_m2 = p.contact_area_m2;
  d.adhesion_fraction = p.adhesion_fraction;
  d.frictional_power_w = p.frictional_power_w;
  copy3(d.force_track_n, p.force_track_n);
  d.method = static_cast<int32_t>(p.method);
}

void fill_forces(rc_wheel_forces& d, const railcontact::StepOutput& s) {
  std::memset(&d, 0, sizeof d);
  const std::size_t max_warnings = static_cast<std::size_t>(std::numeric_limits<int32_t>::max());
  d.n_warnings = static_cast<int32_t>(s.warnings.size() < max_warnings ? s.warnings.size()
                                                                         : max_warnings);
  d.step_index = s.step_index;
  d.time_s = s.time_s;
  d.center_z_m = s.center_z_m;
  d.roll_rad = s.roll_rad;
  d.pitch_rad_per_s = s.pitch_rad_per_s;
  d.server_time_s = s.server_time_s;
  d.marked = s.marked ? 1 : 0;
  for (const railcontact::WheelResult& w : s.wheels) {
    rc_wheel& dw = d.wheels[w.side == railcontact::Side::Right ? RC_RIGHT : RC_LEFT];
    dw.solved = 1;
    copy3(dw.force_track_n, w.force_track_n);
    dw.vertical_approach_m = w.vertical_approach_m;
    dw.min_gap_m = w.min_gap_m;
    dw.load_iterations = static_cast<int32_t>(w.load_iterations);
    dw.n_patches_total = static_cast<int32_t>(w.patches.size());
    const std::size_t kept = w.patches.size() < RC_MAX_PATCHES ? w.patches.size() : RC_MAX_PATCHES;
    dw.n_patches = static_cast<int32_t>(kept);
    for (std::size_t i = 0; i < kept; ++i) {
      fill_patch(dw.patches[i], w.patches[i]);
    }
  }
}

railcontact::WheelsetState state_of(const rc_wheelset_state& in) {
  railcontact::WheelsetState s;
  s.lateral_m = in.lateral_m;
  s.yaw_rad = in.yaw_rad;
  if (in.has_roll_rad != 0) {
    s.roll_rad = in.roll_rad;
  }
  s.forward_m_per_s = in.forward_m_per_s;
  s.lateral_m_per_s = in.lateral_m_per_s;
  s.vertical_m_per_s = in.vertical_m_per_s;
  s.roll_rad_per_s = in.roll_rad_per_s;
  s.yaw_rad_per_s = in.yaw_rad_per_s;
  if (in.has_pitch_rad_per_s != 0) {
    s.pitch_rad_per_s = in.pitch_rad_per_s;
  }
  s.vertical_force_n = in.vertical_force_n;
  return s;
}

}  // namespace

extern "C" {

rc_session* rc_open(const char* target, const char* pair_id, int model, char* err,
                    size_t errlen) {
  return rc_open_secure(target, pair_id, model, nullptr, nullptr, err, errlen);
}

rc_session* rc_open_secure(const char* target, const char* pair_id, int model,
                           const char* tls_ca_file, const char* token, char* err,
                           size_t errlen) {
  if (target == nullptr || pair_id == nullptr) {
    usage(err, errlen, "rc_open needs a target and a pair id");
    return nullptr;
  }
  rc_session* session = nullptr;
  guarded(err, errlen, [&] {
    railcontact::SessionOptions options;
    options.target = target;
    options.pair_id = pair_id;
    options.model = static_cast<railcontact::Model>(model);
    options.client_label = "railcontact-c";
    if (tls_ca_file != nullptr && tls_ca_file[0] != '\0') {
      options.tls = true;
      options.tls_ca_file = tls_ca_file;
    }
    if (token != nullptr) {
      options.token = token;
    }
    session = new rc_session(options);
  });
  return session;
}

int rc_step(rc_session* session, uint64_t step_index, double time_s,
            const rc_wheelset_state* in, rc_wheel_forces* out, char* err, size_t errlen) {
  if (session == nullptr || in == nullptr || out == nullptr) {
    return usage(err, errlen, "rc_step needs a session, an input and an output");
  }
  return guarded(err, errlen, [&] {
    railcontact::StepOutput result =
        session->session.step(step_index, time_s, state_of(*in), in->mark != 0);
    fill_forces(*out, result);
    session->warnings = std::move(result.warnings);
  });
}

int rc_step_warning(const rc_session* session, int32_t index, int32_t* kind, int32_t* side,
                    double* value, double* limit, char* message, size_t message_len,
                    char* err, size_t errlen) {
  if (session == nullptr) {
    return usage(err, errlen, "rc_step_warning needs a session");
  }
  if (message == nullptr && message_len > 0) {
    return usage(err, errlen, "rc_step_warning: message is NULL with message_len > 0");
  }
  const std::size_t count = session->warnings.size();
  if (index < 0 || static_cast<std::size_t>(index) >= count) {
    char what[128];
    std::snprintf(what, sizeof what,
                  "rc_step_warning: index %ld is outside [0, n_warnings = %zu) of the last step",
                  static_cast<long>(index), count);
    return usage(err, errlen, what);
  }
  const railcontact::Warning& w = session->warnings[static_cast<std::size_t>(index)];
  if (kind != nullptr) {
    *kind = static_cast<int32_t>(w.kind);
  }
  if (side != nullptr) {
    *side = !w.side                              ? RC_WHEELSET
            : *w.side == railcontact::Side::Left  ? RC_LEFT
            : *w.side == railcontact::Side::Right ? RC_RIGHT
                                                  : RC_WHEELSET;
  }
  if (value != nullptr) {
    *value = w.value;
  }
  if (limit != nullptr) {
    *limit = w.limit;
  }
  copy_text(message, message_len, w.message);
  clear_err(err, errlen);
  return 0;
}

int rc_rollback(rc_session* session, uint64_t to_step_index, uint64_t* next_step_index,
                char* err, size_t errlen) {
  if (session == nullptr) {
    return usage(err, errlen, "rc_rollback needs a session");
  }
  return guarded(err, errlen, [&] {
    const std::uint64_t next = session->session.rollback(to_step_index);
    if (next_step_index != nullptr) {
      *next_step_index = next;
    }
  });
}

uint64_t rc_next_step_index(const rc_session* session) {
  return session == nullptr ? 0 : session->session.next_step_index();
}

int rc_is_open(const rc_session* session) {
  return session != nullptr && session->session.is_open() ? 1 : 0;
}

void rc_close(rc_session* session) {
  if (session == nullptr) {
    return;
  }
  try {
    session->session.close();
  } catch (...) {
    // Closing reports nothing: the session is freed all the same.
  }
  delete session;
}

}  // extern "C"
