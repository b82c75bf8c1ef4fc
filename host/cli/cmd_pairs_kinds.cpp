// `collide pairs --kind sphere-plane|capsule-sphere`: vector mode for the pair kinds beyond
// spheres (docs/pair-kinds.md) on their CPU references (simd: binary32, simd64: binary64) and
// on ODE's own dCollide (ode). Every backend takes the shapes as ODE keeps them: the values are
// read in binary64 and ODE itself normalizes a plane, or a capsule's axis, before any rounding.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <ode/ode.h>

#include "afu_contract.hpp"
#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/number_csv.hpp"
#include "cli/output_file.hpp"
#include "ode/ode_library.hpp"
#include "pairs/capsule_sphere.hpp"
#include "pairs/sphere_plane.hpp"
#include "util/input_file.hpp"

namespace collide::cli {

namespace {

using pairs::Contact;

// ODE's geoms for one kind, reused for every row.
class OdeGeoms {
 public:
  OdeGeoms()
      : sphere_(dCreateSphere(nullptr, 1)), other_(dCreateSphere(nullptr, 1)), plane_(dCreatePlane(nullptr, 0, 0, 1, 0)),
        capsule_(dCreateCapsule(nullptr, 1, 1)) {}
  ~OdeGeoms() {
    for (dGeomID g : {sphere_, other_, plane_, capsule_}) dGeomDestroy(g);
  }
  OdeGeoms(const OdeGeoms&) = delete;
  OdeGeoms& operator=(const OdeGeoms&) = delete;

  // The plane (a, b, c, d) as ODE keeps it (dGeomPlaneSetParams normalizes as dCreatePlane does).
  void plane(const double in[4], double out[4]) {
    dGeomPlaneSetParams(plane_, in[0], in[1], in[2], in[3]);
    dVector4 q;
    dGeomPlaneGetParams(plane_, q);
    for (int i = 0; i < 4; ++i) out[i] = q[i];
  }
  // The capsule's axis as ODE keeps it: the third column of the rotation dRFromZAxis makes.
  void axis(const double in[3], double out[3]) {
    dMatrix3 R;
    dRFromZAxis(R, in[0], in[1], in[2]);
    dGeomSetRotation(capsule_, R);
    const dReal* q = dGeomGetRotation(capsule_);
    out[0] = q[2];
    out[1] = q[6];
    out[2] = q[10];
  }
  Contact<double> spherePlane(const double* v) {
    dGeomSphereSetRadius(sphere_, v[3]);
    dGeomSetPosition(sphere_, v[0], v[1], v[2]);
    dGeomPlaneSetParams(plane_, v[4], v[5], v[6], v[7]);
    return collide(sphere_, plane_);
  }
  // v: cx, cy, cz, axis (as given), lz, rc, sx, sy, sz, rs.
  Contact<double> capsuleSphere(const double* v) {
    dGeomCapsuleSetParams(capsule_, v[7], v[6]);
    dGeomSetPosition(capsule_, v[0], v[1], v[2]);
    dMatrix3 R;
    dRFromZAxis(R, v[3], v[4], v[5]);
    dGeomSetRotation(capsule_, R);
    dGeomSphereSetRadius(other_, v[11]);
    dGeomSetPosition(other_, v[8], v[9], v[10]);
    return collide(capsule_, other_);
  }

 private:
  static Contact<double> collide(dGeomID a, dGeomID b) {
    dContactGeom g{};
    Contact<double> out;
    if (dCollide(a, b, 1, &g, sizeof(dContactGeom)) == 1) {
      out.hit = true;
      for (int i = 0; i < 3; ++i) {
        out.pos[i] = g.pos[i];
        out.normal[i] = g.normal[i];
      }
      out.depth = g.depth;
    }
    return out;
  }
  dGeomID sphere_, other_, plane_, capsule_;
};

// One kind: its columns, which of them must not be negative (radii, a length), how ODE keeps
// its shapes (`canonical`, in place, binary64), and its references.
struct Kind {
  std::vector<std::string> columns;
  std::vector<int> notNegative;
  std::function<bool(OdeGeoms&, const double* in, double* v)> canonical;  // false: no such shape
  std::function<Contact<double>(OdeGeoms&, const double* in)> ode;       // the row as read
  std::function<Contact<double>(const double* v)> simd64;
  std::function<Contact<float>(const float* v)> simd;
};

Kind kindOf(const std::string& name) {
  if (name == "sphere-plane")
    return {{"cx", "cy", "cz", "r", "nx", "ny", "nz", "d"},
            {3},
            [](OdeGeoms& g, const double* in, double* v) {
              g.plane(in + 4, v + 4);
              return true;
            },
            [](OdeGeoms& g, const double* in) { return g.spherePlane(in); },
            [](const double* v) { return pairs::collideSpherePlane<double>(v, v[3], v + 4); },
            [](const float* v) { return pairs::collideSpherePlane<float>(v, v[3], v + 4); }};
  return {{"cx", "cy", "cz", "ax", "ay", "az", "lz", "rc", "sx", "sy", "sz", "rs"},
          {6, 7, 11},
          [](OdeGeoms& g, const double* in, double* v) {
            if (in[3] == 0 && in[4] == 0 && in[5] == 0) return false;  // an axis of length zero: no capsule
            g.axis(in + 3, v + 3);
            return true;
          },
          [](OdeGeoms& g, const double* in) { return g.capsuleSphere(in); },
          [](const double* v) { return pairs::collideCapsuleSphere<double>(v, v + 3, v[6], v[7], v + 8, v[11]); },
          [](const float* v) { return pairs::collideCapsuleSphere<float>(v, v + 3, v[6], v[7], v + 8, v[11]); }};
}

template <typename T>
std::uint8_t arithFlag(const Contact<T>& k) {
  if (!k.hit) return 0;
  bool bad = !std::isfinite(k.depth);
  for (int i = 0; i < 3; ++i) bad = bad || !std::isfinite(k.pos[i]) || !std::isfinite(k.normal[i]);
  return bad ? contract::REC_ARITH : 0;
}

}  // namespace

int runKindPairs(const PairsOptions& o) {
  return reportErrors("collide pairs", [&]() -> int {
    const std::string what = "--kind " + o.kind;
    if (!o.afu.empty())
      throw std::invalid_argument(what + ": no AFU has " + o.kind + " units yet (docs/pair-kinds.md); use --backend simd, simd64 or ode");
    if (o.backend != "simd" && o.backend != "simd64" && o.backend != "ode")
      throw std::invalid_argument(what + ": backend '" + o.backend + "' has no " + o.kind +
                                  " pairs; use simd (binary32), simd64 or ode (binary64)");
    if (!o.trace.empty()) throw std::invalid_argument("--trace needs --afu DIR");
    const Kind kind = kindOf(o.kind);
    const std::size_t n = kind.columns.size();
    const bool binary32 = o.backend == "simd";
    const LinkFormat fmt = binary32 ? LinkFormat::Binary32 : LinkFormat::Binary64;

    OutputFile out(o.out, OutputFile::Dash::IsStdout);
    std::vector<double> values;
    std::vector<std::uint8_t> unfit;
    const auto readRow = [&](const double* v, const bool* u) {
      for (std::size_t i = 0; i < n; ++i) {
        values.push_back(v[i]);
        unfit.push_back(u[i]);
      }
    };
    if (o.in == "-") {
      readNumberCsv(std::cin, "<stdin>", LinkFormat::Binary64, kind.columns, readRow, Overflow::Flag);
    } else {
      std::ifstream in = util::openInput(o.in);
      readNumberCsv(in, o.in, LinkFormat::Binary64, kind.columns, readRow, Overflow::Flag);
    }

    ode::Library library;
    OdeGeoms geoms;
    const std::size_t rows = values.size() / n;
    std::size_t hits = 0;
    std::vector<std::uint8_t> allFlags;
    allFlags.reserve(rows);
    std::ostream& os = out.stream();
    os << "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n";
    const auto isSize = [&](std::size_t i) {
      for (int s : kind.notNegative)
        if (static_cast<std::size_t>(s) == i) return true;
      return false;
    };
    std::vector<double> v(n);
    std::vector<float> vf(n);
    for (std::size_t k = 0; k < rows; ++k) {
      const double* in = &values[k * n];
      // Flags as for sphere pairs (docs/host.md, "collide pairs"): a NaN or infinity is no
      // contact (8); a value the backend's format cannot hold is flagged (32), and is no contact
      // when it became infinite (8 + 32); a negative radius or length is no shape (32).
      std::uint8_t flags = 0;
      bool compute = true;
      for (std::size_t i = 0; i < n; ++i) {
        v[i] = in[i];
        if (unfit[k * n + i]) flags |= contract::REC_HOST_RANGE;
        if (!std::isfinite(in[i])) {
          flags |= contract::REC_NONFINITE;
          compute = false;
        }
      }
      for (int i : kind.notNegative)
        if (compute && in[i] < 0) {
          flags |= contract::REC_HOST_RANGE;
          compute = false;
        }
      if (compute && !kind.canonical(geoms, in, v.data())) {
        flags |= contract::REC_HOST_RANGE;
        compute = false;
      }
      if (compute && binary32) {
        for (std::size_t i = 0; i < n; ++i) {
          vf[i] = static_cast<float>(v[i]);
          if (std::isinf(vf[i])) {
            flags |= contract::REC_NONFINITE | contract::REC_HOST_RANGE;
            compute = false;
          } else if (v[i] != 0 && vf[i] == 0 && isSize(i)) {
            flags |= contract::REC_HOST_RANGE;  // a radius or length that became zero is another body
          }
        }
      }
      Contact<double> c;
      if (compute && o.backend == "ode") {
        c = kind.ode(geoms, in);
      } else if (compute && binary32) {
        const auto f = kind.simd(vf.data());
        flags |= arithFlag(f);
        c.hit = f.hit;
        for (int i = 0; i < 3; ++i) {
          c.pos[i] = f.pos[i];
          c.normal[i] = f.normal[i];
        }
        c.depth = f.depth;
      } else if (compute) {
        c = kind.simd64(v.data());
      }
      if (compute && !binary32) flags |= arithFlag(c);
      if (c.hit) flags |= contract::REC_HIT;
      hits += c.hit;
      os << k << ',' << int{c.hit};
      for (double x : {c.pos[0], c.pos[1], c.pos[2], c.normal[0], c.normal[1], c.normal[2], c.depth})
        os << ',' << hexFloat(x, fmt);
      os << ',' << int{flags} << '\n';
      allFlags.push_back(flags);
    }
    out.commit();
    std::cerr << "collide pairs: " << rows << " " << o.kind << " pairs, " << hits << " contacts, backend " << o.backend
              << " (" << toString(fmt) << ")\n";
    // Last, so that a flagged pair never passes without a word (as for sphere pairs).
    if (const std::string flagged = flaggedSummary(allFlags); !flagged.empty())
      std::cerr << "collide pairs: flagged " << flagged << "\n";
    return 0;
  });
}

}  // namespace collide::cli
