#pragma once
#include <string>

// The sane range of a sphere and of a scene's numbers: what every backend accepts and what
// we let reach ODE (docs/host.md, "What reaches ODE"). Plain numbers, so the layers below
// ODE (batch, scene, the CPU backends) check them without it.
//
// Coordinates: ODE's hash space files every geom's box under integer cell coordinates, cells
// at least 2^-3 m wide (dHashSpaceSetLevels' default minimum level -3), and asserts when a
// coordinate's cell index leaves the int range ("aabbBound >= dMinIntExact && aabbBound <
// dMaxIntExact", collision_space.cpp): beyond about 2^31 x 0.125 m = 2.7e8 m. 1e6 m keeps two
// orders of magnitude from that, and from binary32 links, whose spacing at 1e6 is 0.0625 m.
// Radii: dGeomSphereSetRadius refuses a negative or NaN radius.
namespace collide::limits {

inline constexpr double kMaxCoordinateM = 1e6;  // |x|, |y|, |z| of a centre
inline constexpr double kMaxRadiusM = 1e6;      // radius in (0, kMaxRadiusM]

// A mass of 1e300 kg or a step of 1e-300 s ends in ODE's quaternion normalisation
// assertion ("bSafeNormalize4Fault", odemath.h) within a step; these ranges are wide guards
// against such typos, not limits of the model.
inline constexpr double kMinMassKg = 1e-9, kMaxMassKg = 1e9;
inline constexpr double kMinDtS = 1e-9, kMaxDtS = 10;

// ODE's broad phase: its hash space (ODE's default) or sweep and prune (axes x, y, z), for a
// scene's pairs path and for `collide spheres --backend ode` alike (ode::createSpace); and its
// quadtree, for `collide spheres` only, since it is made for the world's box
// (world/ode_space_broad_phase.*).
enum class OdeSpaceKind { Hash, SweepAndPrune, QuadTree };
inline const char* toString(OdeSpaceKind k) {
  return k == OdeSpaceKind::Hash ? "hash" : k == OdeSpaceKind::SweepAndPrune ? "sap" : "quadtree";
}

// ODE 0.16's hash space marks tested pairs in an n x ceil(n/8) byte matrix whose size is an
// int (dxHashSpace::collide, collision_space.cpp): from 131,072 spheres on it overflows and ODE
// asserts. Larger worlds go to sweep and prune ("collision": {"space": "sap"}) or world mode.
inline constexpr long long kMaxHashSpaceSpheres = 131'071;
inline constexpr long long hashSpaceTestedBytes(long long n) { return n * ((n + 7) >> 3); }
static_assert(hashSpaceTestedBytes(kMaxHashSpaceSpheres) <= 2'147'483'647LL &&
                  hashSpaceTestedBytes(kMaxHashSpaceSpheres + 1) > 2'147'483'647LL,
              "kMaxHashSpaceSpheres is the largest n whose tested-pairs matrix fits an int");
// Why n spheres do not fit the hash space; each caller adds its own way out.
inline std::string hashSpaceRefusal(long long n) {
  return std::to_string(n) + " spheres, more than ODE's hash space holds (" + std::to_string(kMaxHashSpaceSpheres) +
         ": its tested-pairs matrix of n x ceil(n/8) bytes, " + std::to_string(hashSpaceTestedBytes(n) / (1 << 20)) +
         " MiB here, passes ODE's int range)";
}

// What `collide run` needs at least for a scene of n spheres (bench/results/scale, peak RSS of
// runs from 1,000 to 1,000,000 spheres): about 62 MiB for the program and its libraries, then
// per sphere its ODE body, geom and space entries, and the step's pairs, contacts and joints:
// 3.3-3.9 KiB a sphere in the poured piles (about 1.7 contacts a sphere a step) from 64,000
// spheres up, more in close-packed scenes (the diamond at hMax 46, 5.7 contacts a sphere: 10
// KiB); and with the hash space its tested-pairs matrix on top. kRunBytesPerSphere is below
// every measurement, so a scene refused up front would certainly not have fitted, instead of
// being killed by the kernel half-way.
inline constexpr long long kRunBaseBytes = 64LL << 20;
inline constexpr long long kRunBytesPerSphere = 3072;
inline long long runBytes(long long n, OdeSpaceKind space) {
  return kRunBaseBytes + n * kRunBytesPerSphere + (space == OdeSpaceKind::Hash ? hashSpaceTestedBytes(n) : 0);
}
// Empty if a run of n spheres fits in `available` bytes, else why not.
inline std::string memoryRefusal(long long n, OdeSpaceKind space, unsigned long long available) {
  const long long need = runBytes(n, space);
  if (need <= 0 || static_cast<unsigned long long>(need) <= available) return "";
  auto mib = [](unsigned long long b) { return std::to_string(b >> 20) + " MiB"; };
  return std::to_string(n) + " spheres need at least about " + mib(static_cast<unsigned long long>(need)) + " (" +
         std::to_string(kRunBytesPerSphere) + " bytes a sphere" +
         (space == OdeSpaceKind::Hash ? " and " + mib(static_cast<unsigned long long>(hashSpaceTestedBytes(n))) +
                                            " for the hash space's tested-pairs matrix"
                                      : std::string()) +
         "), more than the " + mib(available) + " this machine has available";
}

inline bool saneCoordinate(double v) { return v >= -kMaxCoordinateM && v <= kMaxCoordinateM; }  // false for NaN
inline bool saneRadius(double r) { return r > 0 && r <= kMaxRadiusM; }

}  // namespace collide::limits
