// warnings_cpp: the plausibility warnings through the C++ class
// (railcontact::StepOutput::warnings), for tests/end_to_end/cpp_client.rs.
//
// The same steps as warnings_c.c on the built-in pair with Hertz+FASTSIM,
// 3 mm to the right at 30 m/s and 60 kN a wheel: step 0 plausible, step 1
// with the pitch rate 1.05 x (-V / 0.46 m) prescribed, step 2 with a roll
// of 1 mrad prescribed. Prints on stdout "step=K label=L n_warnings=N" per
// step and per warning "warning step=K index=I kind=.. side=..
// field=PATH value=.. limit=.. message=TEXT" (side -1 for the wheelset, 0
// left, 1 right, as in the C interface). Exits 1 on an exception.
//
// Usage: warnings_cpp TARGET
#include <cstdio>
#include <exception>

#include "railcontact/cosim.hpp"

namespace {

int side_code(const railcontact::Warning& w) {
  if (!w.side) return -1;
  return *w.side == railcontact::Side::Left ? 0 : 1;
}

void report(std::uint64_t k, const char* label, const railcontact::StepOutput& out) {
  std::printf("step=%llu label=%s n_warnings=%zu\n", static_cast<unsigned long long>(k), label,
              out.warnings.size());
  for (std::size_t i = 0; i < out.warnings.size(); ++i) {
    const railcontact::Warning& w = out.warnings[i];
    std::printf(
        "warning step=%llu index=%zu kind=%d side=%d field=%s value=%.17g limit=%.17g "
        "message=%s\n",
        static_cast<unsigned long long>(k), i, static_cast<int>(w.kind), side_code(w),
        w.field.c_str(), w.value, w.limit, w.message.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s TARGET\n", argv[0]);
    return 2;
  }
  try {
    railcontact::SessionOptions options;
    options.target = argv[1];
    options.model = railcontact::Model::HertzFastsim;
    railcontact::CoSimSession session(options);

    railcontact::WheelsetState state;
    state.lateral_m = 0.003;
    state.forward_m_per_s = 30.0;
    state.vertical_force_n = 60e3;
    report(0, "plausible", session.step(0, 0.0, state));

    railcontact::WheelsetState pitch = state;
    pitch.pitch_rad_per_s = -30.0 / 0.46 * 1.05;
    report(1, "pitch", session.step(1, 1e-3, pitch));

    railcontact::WheelsetState roll = state;
    roll.roll_rad = 0.001;
    report(2, "roll", session.step(2, 2e-3, roll));

    session.close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAIL: %s\n", e.what());
    return 1;
  }
  return std::fflush(stdout) == 0 ? 0 : 1;
}
