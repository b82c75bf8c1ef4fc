#pragma once
// What we let reach ODE: the documented sane range of a sphere (docs/host.md, "What
// reaches ODE"). ODE's hash space files every geom's box under integer cell coordinates,
// cells at least 2^-3 m wide (dHashSpaceSetLevels' default minimum level -3), and asserts
// when a coordinate's cell index leaves the int range ("aabbBound >= dMinIntExact &&
// aabbBound < dMaxIntExact", collision_space.cpp): beyond about 2^31 x 0.125 m = 2.7e8 m.
// 1e6 m keeps two orders of magnitude from that, and from binary32 links, whose spacing
// at 1e6 is already 0.0625 m. dGeomSphereSetRadius refuses a negative or NaN radius.
namespace collide::ode {

inline constexpr double kMaxCoordinateM = 1e6;  // |x|, |y|, |z| of a centre
inline constexpr double kMaxRadiusM = 1e6;      // radius in (0, kMaxRadiusM]

// A mass of 1e300 kg or a step of 1e-300 s ends in ODE's quaternion normalisation
// assertion ("bSafeNormalize4Fault", odemath.h) within a step; these ranges are wide guards
// against such typos, not limits of the model.
inline constexpr double kMinMassKg = 1e-9, kMaxMassKg = 1e9;
inline constexpr double kMinDtS = 1e-9, kMaxDtS = 10;

inline bool saneCoordinate(double v) { return v >= -kMaxCoordinateM && v <= kMaxCoordinateM; }  // false for NaN
inline bool saneRadius(double r) { return r > 0 && r <= kMaxRadiusM; }

}  // namespace collide::ode
