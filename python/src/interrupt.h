// Ctrl-C during a long solve. The solvers run with the GIL released, so Python's signal handlers
// wait until they return. An Interruptible call gives the solver a hook (its progress callback)
// that, on the calling thread, runs the pending handlers; when one raises (KeyboardInterrupt) the
// hook throws to abandon the solve, and the worker threads' hooks throw too at their next call.
// The Python exception is raised from the call once the solver has unwound.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <exception>
#include <memory>
#include <stdexcept>
#include <thread>

namespace plateball::python {

class Interruptible {
 public:
  Interruptible() : state_(std::make_shared<State>()) {}

  /// The hook: call it from the solver's progress callback (any thread, GIL not held).
  void Check() const {
    if (state_->raised.load()) throw std::runtime_error("interrupted");
    if (std::this_thread::get_id() != state_->caller) return;  // handlers run on the main thread only
    pybind11::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() == 0) return;
    state_->error = std::make_exception_ptr(pybind11::error_already_set());
    state_->raised.store(true);
    throw std::runtime_error("interrupted");
  }

  /// The hook for a solver that asks whether to stop (and then returns with a status): true once a
  /// handler raised (any thread, GIL not held).
  bool Requested() const {
    try {
      Check();
      return false;
    } catch (const std::runtime_error&) {
      return true;
    }
  }

  /// After a solver that stopped on Requested() returned: re-raises the handler's Python
  /// exception, if one was raised.
  void RaiseIfRequested() const {
    if (state_->raised.load()) std::rethrow_exception(state_->error);
  }

  /// Runs `solve()`; when the hook fired, re-raises the handler's Python exception instead of
  /// the solver's unwinding.
  template <class Solve>
  auto Run(Solve&& solve) const {
    try {
      return solve();
    } catch (...) {
      if (state_->raised.load()) std::rethrow_exception(state_->error);
      throw;
    }
  }

 private:
  struct State {
    std::thread::id caller = std::this_thread::get_id();
    std::atomic<bool> raised{false};
    std::exception_ptr error;
  };
  std::shared_ptr<State> state_;
};

}  // namespace plateball::python
