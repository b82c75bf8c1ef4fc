#pragma once
// A fork-join team for the tuned grid (world/tuned_world.hpp): run(job) calls job(t) once for
// each t in [0, size()), the caller being thread 0, and returns when every call has. The
// workers are started once, so repeated collisions pay no thread start-up, and joined by the
// destructor. A job's exception is rethrown by run (the first one, if several threw).
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace collide::world {

class ThreadTeam {
 public:
  explicit ThreadTeam(unsigned threads);
  ~ThreadTeam();
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()) + 1; }
  void run(const std::function<void(unsigned)>& job);
  // std::thread::hardware_concurrency, at least 1 (it may say 0: unknown).
  static unsigned hardwareThreads();

 private:
  void serve(unsigned t);
  void call(unsigned t);

  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable start_, done_;
  const std::function<void(unsigned)>* job_ = nullptr;
  std::uint64_t generation_ = 0;  // bumped by each run, so a worker takes each job once
  unsigned pending_ = 0;          // workers still in the current job
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace collide::world
