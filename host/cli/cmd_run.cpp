#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/run_report.hpp"
#include "collide/backend_factory.hpp"
#include "collide/ode_backend.hpp"
#include "collide/simd_backend.hpp"
#include "driver/afu_factory.hpp"
#include "ode/simulation.hpp"
#include "scene/scene.hpp"

namespace collide::cli {

void printTiming(std::ostream& os, std::int64_t ns, std::uint64_t pairs, std::uint64_t contacts) {
  os << std::fixed << std::setprecision(3) << ns / 1e6 << " ms total, ";
  if (pairs) os << std::setprecision(1) << static_cast<double>(ns) / pairs << " ns/pair, ";
  else os << "- ns/pair, ";
  if (contacts) os << std::setprecision(1) << static_cast<double>(ns) / contacts << " ns/collision";
  else os << "- ns/collision";
}

namespace {

template <typename F>
std::int64_t timeNs(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int runScene(const RunOptions& o) {
  try {
    scene::Scene sc = scene::loadScene(o.scene);
    if (o.backend) sc.backend = *o.backend;
    if (o.steps) sc.steps = *o.steps;

    BackendRequest req{sc.backend, sc.afuDir, sc.link};
    auto backend = makeBackend(req);  // rtl without an AFU throws AfuUnavailable here

    std::cout << "scene " << sc.name << ": " << sc.spheres.size() << " spheres, " << sc.steps
              << " steps, dt " << sc.dt << ", backend " << backend->name() << ", link "
              << (sc.backend == "rtl" ? sc.link.name : std::string("not simulated (CPU backend)")) << "\n";

    // The same pairs through ODE's collider and the simd batch, timed each step.
    OdeBackend ode;
    SimdBackend simd;
    ContactSet odeOut, simdOut;
    RunTotals tot;
    std::int64_t stepOdeNs = 0, stepSimdNs = 0;
    std::uint64_t stepMismatch = 0;

    ode::Simulation sim(sc, *backend);
    sim.setBatchObserver([&](const SphereTable& t, const PairList& p, const ContactSet&) {
      stepOdeNs = timeNs([&] { ode.collide(t, p, odeOut); });
      stepSimdNs = timeNs([&] { simd.collide(t, p, simdOut); });
      stepMismatch = 0;
      for (std::size_t k = 0; k < p.size(); ++k) stepMismatch += odeOut.hit[k] != simdOut.hit[k];
    });

    std::ofstream csv;
    if (!o.out.empty()) {
      csv.open(o.out);
      if (!csv) throw std::runtime_error(o.out + ": cannot write");
      csv << "step,pairs,contacts,other_contacts,backend_ns,ode_ns,simd_ns,hit_mismatches\n";
    }
    for (long long s = 0; s < sc.steps; ++s) {
      const auto st = sim.step();
      tot.pairs += st.pairsTested;
      tot.contacts += st.contacts;
      tot.otherContacts += st.otherContacts;
      tot.backendNs += st.backendNs;
      tot.odeNs += stepOdeNs;
      tot.simdNs += stepSimdNs;
      tot.hitMismatches += stepMismatch;
      if (o.perStep)
        std::cout << "step " << st.step << ": " << st.pairsTested << " pairs, " << st.contacts << " contacts"
                  << (st.otherContacts ? " (+" + std::to_string(st.otherContacts) + " plane)" : "")
                  << ", ode " << stepOdeNs << " ns, simd " << stepSimdNs << " ns\n";
      if (csv.is_open())
        csv << st.step << ',' << st.pairsTested << ',' << st.contacts << ',' << st.otherContacts << ','
            << st.backendNs << ',' << stepOdeNs << ',' << stepSimdNs << ',' << stepMismatch << '\n';
    }

    std::cout << "pairs tested : " << tot.pairs << " sphere/sphere candidates from the broad phase\n"
              << "contacts     : " << tot.contacts << " sphere/sphere";
    if (sc.groundZ) std::cout << " (+" << tot.otherContacts << " sphere/plane on the CPU)";
    std::cout << "\nODE collider : ";
    printTiming(std::cout, tot.odeNs, tot.pairs, tot.contacts);
    std::cout << "  (dCollide on the world's dSphere geoms, binary64)\nsimd batch   : ";
    printTiming(std::cout, tot.simdNs, tot.pairs, tot.contacts);
    std::cout << "  (gather + binary32 SoA kernel)\n"
              << "simd vs ode  : " << tot.hitMismatches << " pairs disagree on hit\n"
              << "backend " << backend->name() << "  : ";
    printTiming(std::cout, tot.backendNs, tot.pairs, tot.contacts);
    std::cout << "  (the backend that drove the simulation)\n";
    return 0;
  } catch (const driver::AfuUnavailable& e) {
    std::cerr << "collide run: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "collide run: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace collide::cli
