// `collide pairs --kind sphere-plane`: vector mode for sphere/plane pairs (docs/pair-kinds.md)
// on the CPU references (simd: binary32, simd64: binary64) and on ODE's own dCollide (ode).
#include <cmath>
#include <cstdint>
#include <fstream>
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
#include "pairs/sphere_plane.hpp"
#include "util/input_file.hpp"

namespace collide::cli {

namespace {

struct PlaneRow {
  double c[3], r, plane[4];  // the plane as read: ODE normalizes it (OdePair::normalized)
  bool unfit[8];
};

// ODE's sphere and plane, reused for every row: dGeomPlaneSetParams normalizes (a, b, c, d)
// as dCreatePlane does, so every backend takes the plane ODE keeps.
class OdePair {
 public:
  OdePair() : sphere_(dCreateSphere(nullptr, 1)), plane_(dCreatePlane(nullptr, 0, 0, 1, 0)) {}
  ~OdePair() {
    dGeomDestroy(sphere_);
    dGeomDestroy(plane_);
  }
  OdePair(const OdePair&) = delete;
  OdePair& operator=(const OdePair&) = delete;

  void normalized(const double in[4], double out[4]) {
    dGeomPlaneSetParams(plane_, in[0], in[1], in[2], in[3]);
    dVector4 q;
    dGeomPlaneGetParams(plane_, q);
    for (int i = 0; i < 4; ++i) out[i] = q[i];
  }
  pairs::SpherePlaneContact<double> collide(const double c[3], double r, const double in[4]) {
    dGeomSphereSetRadius(sphere_, r);
    dGeomSetPosition(sphere_, c[0], c[1], c[2]);
    dGeomPlaneSetParams(plane_, in[0], in[1], in[2], in[3]);
    dContactGeom g{};
    pairs::SpherePlaneContact<double> out;
    if (dCollide(sphere_, plane_, 1, &g, sizeof(dContactGeom)) == 1) {
      out.hit = true;
      for (int i = 0; i < 3; ++i) {
        out.pos[i] = g.pos[i];
        out.normal[i] = g.normal[i];
      }
      out.depth = g.depth;
    }
    return out;
  }

 private:
  dGeomID sphere_, plane_;
};

template <typename T>
std::uint8_t arithFlag(const pairs::SpherePlaneContact<T>& k) {
  if (!k.hit) return 0;
  bool bad = !std::isfinite(k.depth);
  for (int i = 0; i < 3; ++i) bad = bad || !std::isfinite(k.pos[i]);
  return bad ? contract::REC_ARITH : 0;
}

}  // namespace

int runSpherePlanePairs(const PairsOptions& o) {
  return reportErrors("collide pairs", [&]() -> int {
    if (!o.afu.empty())
      throw std::invalid_argument("--kind sphere-plane: no AFU has sphere/plane units yet (docs/pair-kinds.md); "
                                  "use --backend simd, simd64 or ode");
    if (o.backend != "simd" && o.backend != "simd64" && o.backend != "ode")
      throw std::invalid_argument("--kind sphere-plane: backend '" + o.backend +
                                  "' has no sphere/plane pairs; use simd (binary32), simd64 or ode (binary64)");
    if (!o.trace.empty()) throw std::invalid_argument("--trace needs --afu DIR");
    const bool binary32 = o.backend == "simd";
    const LinkFormat fmt = binary32 ? LinkFormat::Binary32 : LinkFormat::Binary64;

    OutputFile out(o.out, OutputFile::Dash::IsStdout);
    std::vector<PlaneRow> rows;
    const auto readRow = [&](const double* v, const bool* unfit) {
      PlaneRow r{};
      for (int i = 0; i < 3; ++i) r.c[i] = v[i];
      r.r = v[3];
      for (int i = 0; i < 4; ++i) r.plane[i] = v[4 + i];
      for (int i = 0; i < 8; ++i) r.unfit[i] = unfit[i];
      rows.push_back(r);
    };
    const std::vector<std::string> columns = {"cx", "cy", "cz", "r", "nx", "ny", "nz", "d"};
    // Read in binary64: the plane is normalized there, as ODE does, before any rounding.
    if (o.in == "-") {
      readNumberCsv(std::cin, "<stdin>", LinkFormat::Binary64, columns, readRow, Overflow::Flag);
    } else {
      std::ifstream in = util::openInput(o.in);
      readNumberCsv(in, o.in, LinkFormat::Binary64, columns, readRow, Overflow::Flag);
    }

    ode::Library library;
    OdePair ode;
    std::size_t hits = 0, flaggedPairs = 0, flagged[3] = {0, 0, 0};
    std::ostream& os = out.stream();
    os << "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const PlaneRow& row = rows[k];
      // Flags as for sphere pairs (docs/host.md, "collide pairs"): a NaN or infinity is no
      // contact (8); a value the backend's format cannot hold is flagged (32), and is no contact
      // when it became infinite (8 + 32); a negative radius is no sphere (32).
      std::uint8_t flags = 0;
      bool compute = true;
      double v[8] = {row.c[0], row.c[1], row.c[2], row.r, row.plane[0], row.plane[1], row.plane[2], row.plane[3]};
      for (int i = 0; i < 8; ++i) {
        if (row.unfit[i]) flags |= contract::REC_HOST_RANGE;
        if (!std::isfinite(v[i])) {
          flags |= contract::REC_NONFINITE;
          compute = false;
        }
      }
      if (compute) {
        ode.normalized(row.plane, v + 4);  // the plane ODE keeps, in binary64
        if (binary32) {
          for (int i = 0; i < 8; ++i) {
            const float f = static_cast<float>(v[i]);
            if (std::isinf(f)) {
              flags |= contract::REC_NONFINITE | contract::REC_HOST_RANGE;
              compute = false;
            } else if (i == 3 && v[i] != 0 && f == 0) {
              flags |= contract::REC_HOST_RANGE;  // a radius that became zero is another body
            }
            v[i] = f;
          }
        }
        if (v[3] < 0) {
          flags |= contract::REC_HOST_RANGE;
          compute = false;
        }
      }
      pairs::SpherePlaneContact<double> c;
      if (compute && o.backend == "ode") {
        c = ode.collide(v, v[3], row.plane);
      } else if (compute && binary32) {
        const float cf[3] = {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
        const float pf[4] = {static_cast<float>(v[4]), static_cast<float>(v[5]), static_cast<float>(v[6]),
                             static_cast<float>(v[7])};
        const auto f = pairs::collideSpherePlane<float>(cf, static_cast<float>(v[3]), pf);
        flags |= arithFlag(f);
        c.hit = f.hit;
        for (int i = 0; i < 3; ++i) {
          c.pos[i] = f.pos[i];
          c.normal[i] = f.normal[i];
        }
        c.depth = f.depth;
      } else if (compute) {
        c = pairs::collideSpherePlane<double>(v, v[3], v + 4);
      }
      if (compute && !binary32) flags |= arithFlag(c);
      if (c.hit) flags |= contract::REC_HIT;
      hits += c.hit;
      os << k << ',' << int{c.hit};
      for (double x : {c.pos[0], c.pos[1], c.pos[2], c.normal[0], c.normal[1], c.normal[2], c.depth})
        os << ',' << hexFloat(x, fmt);
      os << ',' << int{flags} << '\n';
      flaggedPairs += (flags & (contract::REC_NONFINITE | contract::REC_ARITH | contract::REC_HOST_RANGE)) != 0;
      flagged[0] += (flags & contract::REC_NONFINITE) != 0;
      flagged[1] += (flags & contract::REC_ARITH) != 0;
      flagged[2] += (flags & contract::REC_HOST_RANGE) != 0;
    }
    out.commit();
    std::cerr << "collide pairs: " << rows.size() << " sphere/plane pairs, " << hits << " contacts, backend "
              << o.backend << " (" << toString(fmt) << ")\n";
    // Last, so that a flagged pair never passes without a word (as for sphere pairs).
    if (flaggedPairs > 0) {
      std::cerr << "collide pairs: flagged " << flaggedPairs << (flaggedPairs == 1 ? " pair:" : " pairs:");
      const char* what[3] = {"non-finite input (8)", "arithmetic overflow or invalid (16)",
                             "outside the host's range or the link format (32)"};
      const char* sep = " ";
      for (int i = 0; i < 3; ++i) {
        if (flagged[i] == 0) continue;
        std::cerr << sep << flagged[i] << " " << what[i];
        sep = ", ";
      }
      std::cerr << "\n";
    }
    return 0;
  });
}

}  // namespace collide::cli
