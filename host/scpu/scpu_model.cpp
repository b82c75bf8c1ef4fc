#include "scpu/scpu_model.hpp"

#include <cmath>
#include <stdexcept>

#include "afu_contract.hpp"

namespace collide::scpu {

namespace {
EmulatedPreset preset(const char* name, const format::NumberFormat& f, LinkFormat link,
                      DistanceMethod m = DistanceMethod::SqrtThenRecip) {
  return {name, ComputeArith{f, numberFormat(link), m}, link};
}
}  // namespace

const std::vector<EmulatedPreset>& emulatedPresets() {
  // The formats of ScpuConfig's presets: fp24 is (8, 16) computed on a binary32 link.
  static const std::vector<EmulatedPreset> all = {
      preset("fp32", format::kBinary32, LinkFormat::Binary32),
      preset("fp32-robust", format::kBinary32, LinkFormat::Binary32, DistanceMethod::Robust),
      preset("fp24", format::NumberFormat{8, 16}, LinkFormat::Binary32),
      preset("fp16", format::kBinary16, LinkFormat::Binary16),
      preset("fp16-robust", format::kBinary16, LinkFormat::Binary16, DistanceMethod::Robust),
      preset("bf16", format::kBFloat16, LinkFormat::BFloat16),
      preset("fp64", format::kBinary64, LinkFormat::Binary64),
  };
  return all;
}

std::optional<std::string> modelBackendPreset(const std::string& backendName) {
  const std::string prefix = kModelBackendPrefix;
  if (backendName.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  return backendName.substr(prefix.size());
}

const EmulatedPreset& emulatedPreset(const std::string& name) {
  for (const auto& p : emulatedPresets())
    if (p.name == name) return p;
  std::string known;
  for (const auto& p : emulatedPresets()) known += (known.empty() ? "" : ", ") + p.name;
  std::string why;
  if (name == "fp32-nr")
    why = ": its roots are Newton-Raphson iterations, not correctly rounded, which binary64 does not reproduce bit "
          "for bit; use the rtl backend with an AFU of that preset";
  else if (name == "fp32-rsqrt-dr")
    why = ": rsqrt(d2) is one rounding of 1/sqrt(x), which binary64's sqrt then divide cannot reproduce bit for bit "
          "everywhere; use the rtl backend with an AFU of that preset";
  throw std::invalid_argument("SCPU preset '" + name + "' is not emulated on the CPU" + why + " (emulated: " + known +
                              ")");
}

void contactPath(RoundedArith& c, const double p1[4], const double p2[4], const double u[3], double rs, double d,
                 double w, double out[7]) {
  const double rdiff = c.sub(p2[3], p1[3]);
  const double depth = c.sub(rs, d);
  const double k = c.mul(0.5, c.sub(rdiff, d));
  for (int i = 0; i < 3; ++i) {
    const double n = c.mul(u[i], w);
    out[i] = c.add(p1[i], c.mul(n, k));
    out[3 + i] = n;
  }
  out[6] = depth;
}

PairResult collidePair(const ComputeArith& a, const double s1[4], const double s2[4]) {
  PairResult r;
  bool nonFinite = false;
  for (int k = 0; k < 4; ++k) nonFinite = nonFinite || !std::isfinite(s1[k]) || !std::isfinite(s2[k]);
  // base: the operators every result reports; path: those only a Contact reports
  // (docs/scpu.md, "Flags").
  RoundedArith base(a.compute), path(a.compute);
  // link -> compute: hardware (and flags) only when the formats differ
  const bool converts = a.compute != a.link;
  double p1[4], p2[4];
  for (int k = 0; k < 4; ++k) {
    p1[k] = converts ? base.convert(s1[k]) : s1[k];
    p2[k] = converts ? base.convert(s2[k]) : s2[k];
  }
  double u[3] = {base.sub(p1[0], p2[0]), base.sub(p1[1], p2[1]), base.sub(p1[2], p2[2])};
  const double rs = base.add(p1[3], p2[3]);
  auto sumOfSquares = [&](const double v[3]) {  // ODE's order: (dx*dx + dy*dy) + dz*dz
    const double sx = base.mul(v[0], v[0]), sy = base.mul(v[1], v[1]), sz = base.mul(v[2], v[2]);
    return base.add(base.add(sx, sy), sz);
  };
  double d = 0, w = 0;
  switch (a.distance) {
    case DistanceMethod::SqrtThenRecip:
      d = base.sqrt(sumOfSquares(u));
      w = path.div(1.0, d);
      break;
    case DistanceMethod::Robust: {
      const int e = scaleExponent(u);
      for (double& x : u) x = base.scale(x, -e);
      const double ds = base.sqrt(sumOfSquares(u));
      d = base.scale(ds, e);
      w = path.div(1.0, ds);
      break;
    }
    case DistanceMethod::Rsqrt:
      throw std::invalid_argument("the CPU SCPU model does not compute rsqrt(d2) (not reproducible in binary64)");
  }
  const bool le = d <= rs;          // a quiet compare: false with a NaN
  const bool notPositive = d <= 0;  // zero of either sign; d is never negative otherwise
  if (!le) {
    r.kind = contract::KIND_SEPARATED;
  } else if (notPositive) {
    r.kind = contract::KIND_COINCIDENT;
    r.v[0] = p1[0]; r.v[1] = p1[1]; r.v[2] = p1[2];
    r.v[3] = 1.0;
    r.v[6] = rs;
  } else {
    r.kind = contract::KIND_CONTACT;
    contactPath(path, p1, p2, u, rs, d, w, r.v);
    r.d = d;
    r.w = w;
  }
  r.hit = le;
  const bool arith = base.overflowOrInvalid() || (r.kind == contract::KIND_CONTACT && path.overflowOrInvalid());
  r.flags = static_cast<std::uint8_t>((le ? contract::REC_HIT : 0u) | (r.kind << contract::REC_KIND_SHIFT) |
                                      (nonFinite ? contract::REC_NONFINITE : 0u) | (arith ? contract::REC_ARITH : 0u));
  return r;  // compute -> link widens exactly
}

}  // namespace collide::scpu
