#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "certify/coverage.h"
#include "certify/window.h"
#include "check.h"
#include "parallel_for.h"
#include "plateball/isoparallel_certificate.h"
#include "plateball/so3.h"

namespace plateball {

namespace {

using internal::CertifyPoint;

// CPU time of the calling thread (a piece runs on one thread).
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The cap of the certificate, or a reason why there is none (then `message` is set).
double LengthCap(const IsoparallelSummary& solved, const IsoparallelCertificateOptions& options, std::string* message) {
  if (options.length_cap > 0.0) return options.length_cap;
  if (!solved.IsSolutionUsable()) {
    *message = "no solution to set the cap from (the solver: " + solved.message + "); give length_cap instead";
    return 0.0;
  }
  return options.cap_factor * (1.0 + 1e-4) * solved.Shortest().length;
}

// Adds a piece's proved solutions, once each (pieces meet on their faces).
void AddProved(const IsoparallelSummary& solved,
               PendulumRegime regime,
               const std::vector<CertifyPoint>& found,
               std::vector<CertifiedSolution>* out) {
  for (const CertifyPoint& p : found) {
    const bool seen = std::any_of(out->begin(), out->end(), [&](const CertifiedSolution& c) {
      return c.regime == regime &&
             internal::SamePath(regime, {c.rate, c.modulus, c.phase, c.length}, p, internal::kSamePathTolerance);
    });
    if (seen) continue;
    // The solver's parameters are polished to 1e-12 in the residual, the proved ones by Newton.
    out->push_back({regime, p[0], p[1], p[2], p[3], internal::MatchingSolution(solved.solutions, regime, p, 1e-6)});
  }
}

// Runs every piece (in parallel, each to the next free thread: their costs differ by 100x), fills
// `pieces` and the proved solutions.
void RunPieces(const IsoparallelSummary& solved,
               const internal::CertifyTarget& target,
               const std::vector<internal::CoveragePiece>& plan,
               const IsoparallelCertificateOptions& options,
               IsoparallelCertificate* out) {
  const int n = static_cast<int>(plan.size());
  std::vector<internal::CoveragePieceResult> results(plan.size());
  out->pieces.assign(plan.size(), {});
  std::mutex done_mutex;
  int done = 0;
  // Once the caller's hook said stop, every piece's next question is answered without it.
  std::atomic<bool> stopped{false};
  const internal::CertifyInterrupt interrupt = [&] {
    if (!stopped.load() && options.interrupted && options.interrupted()) stopped.store(true);
    return stopped.load();
  };
  internal::ParallelForDynamic(n, options.threads, [&](int i) {
    IsoparallelCertificatePiece& p = out->pieces[i];
    p.name = plan[i].Name();
    if (interrupt()) {
      p.result = "not run: interrupted";
      return;
    }
    const double cpu = ThreadCpuSeconds();
    results[i] = internal::RunCoveragePiece(target, plan[i], out->length_cap, options.max_boxes, interrupt);
    p.closed = results[i].closed;
    p.result = results[i].result;
    p.boxes = results[i].boxes;
    p.resolved_volume = std::min(results[i].resolved_volume, 1.0);  // a sum of shares: rounding can pass 1
    p.proved = static_cast<int>(results[i].found.size());
    p.cpu_seconds = ThreadCpuSeconds() - cpu;
    const std::lock_guard<std::mutex> lock(done_mutex);
    ++done;
    if (options.progress) options.progress(p, done, n);
  });
  for (std::size_t i = 0; i < plan.size(); ++i) {
    AddProved(solved, plan[i].regime, results[i].found, &out->solutions);
    out->boxes += out->pieces[i].boxes;
    out->cpu_seconds += out->pieces[i].cpu_seconds;
  }
  std::sort(out->solutions.begin(), out->solutions.end(), [](const CertifiedSolution& a, const CertifiedSolution& b) {
    return a.length < b.length;
  });
  if (stopped.load()) out->status = IsoparallelCertificateStatus::kInterrupted;
}

// The status from the pieces and the solver's list.
void Conclude(const IsoparallelSummary& solved, IsoparallelCertificate* out) {
  for (std::size_t i = 0; i < solved.solutions.size(); ++i) {
    if (solved.solutions[i].length > out->length_cap) continue;
    const bool proved = std::any_of(out->solutions.begin(), out->solutions.end(), [&](const CertifiedSolution& c) {
      return c.solver_index == static_cast<int>(i);
    });
    if (!proved) out->solver_unproved.push_back(static_cast<int>(i));
  }
  const auto open = std::find_if(
      out->pieces.begin(), out->pieces.end(), [](const IsoparallelCertificatePiece& p) { return !p.closed; });
  if (out->status == IsoparallelCertificateStatus::kInterrupted) {
    const long closed = std::count_if(
        out->pieces.begin(), out->pieces.end(), [](const IsoparallelCertificatePiece& p) { return p.closed; });
    out->message = "interrupted: " + std::to_string(closed) + " of " + std::to_string(out->pieces.size()) +
                   " pieces closed before the stop; nothing is claimed about the others";
    return;
  }
  out->status = IsoparallelCertificateStatus::kIncomplete;
  if (open != out->pieces.end()) {
    out->message = "not closed: " + open->name + ": " + open->result;
  } else if (!out->solver_unproved.empty()) {
    const int i = out->solver_unproved.front();
    out->message = "the solver's solution #" + std::to_string(i + 1) + " (length " +
                   internal::FormatNumber(solved.solutions[i].length) +
                   ") is not among the proved ones (a contradiction: please report it)";
  } else {
    out->status = IsoparallelCertificateStatus::kComplete;
    out->message.clear();
  }
}

}  // namespace

std::string ToString(IsoparallelCertificateStatus status) {
  switch (status) {
    case IsoparallelCertificateStatus::kNotRun:
      return "not_run";
    case IsoparallelCertificateStatus::kComplete:
      return "complete";
    case IsoparallelCertificateStatus::kIncomplete:
      return "incomplete";
    case IsoparallelCertificateStatus::kNotApplicable:
      return "not_applicable";
    case IsoparallelCertificateStatus::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string IsoparallelCertificateOptions::Validate() const {
  if (!(cap_factor >= 1.0 && cap_factor <= IsoparallelOptions::kMaxLengthCapFactor))
    return internal::InvalidValueMessage("cap_factor", cap_factor, "must be in [1, 10]");
  if (!(length_cap >= 0.0 && length_cap <= 1e3))
    return internal::InvalidValueMessage("length_cap", length_cap, "must be in [0, 1000] (0: from cap_factor)");
  if (!(max_boxes >= 1 && max_boxes <= kMaxBoxes))
    return internal::InvalidValueMessage("max_boxes", max_boxes, "must be in [1, 10000000000]");
  if (!(threads >= 1 && threads <= kMaxThreads))
    return internal::InvalidValueMessage("threads", threads, "must be in [1, " + std::to_string(kMaxThreads) + "]");
  return "";
}

int IsoparallelCertificate::MissedBySolver() const {
  return static_cast<int>(
      std::count_if(solutions.begin(), solutions.end(), [](const CertifiedSolution& s) { return s.solver_index < 0; }));
}

IsoparallelCertificate CertifyIsoparallel(const IsoparallelSummary& solved,
                                          const IsoparallelCertificateOptions& options) {
  if (const std::string error = options.Validate(); !error.empty()) throw std::invalid_argument(error);
  const auto start = std::chrono::steady_clock::now();
  IsoparallelCertificate out;
  out.status = IsoparallelCertificateStatus::kNotApplicable;
  out.message.clear();
  const internal::CertifyTarget target = internal::CertifyTargetOf(solved.problem);
  if (LogSO3(target.target).norm() <= solved.options.tolerance) {
    out.message = "identity target: the family enumeration is complete already (IsoparallelSummary::complete)";
    return out;
  }
  out.length_cap = LengthCap(solved, options, &out.message);
  if (!out.message.empty()) return out;
  const internal::CoveragePlan plan = internal::PlanCoverage(target, out.length_cap);
  if (!plan.message.empty()) throw std::invalid_argument(plan.message);
  out.straight_residual = plan.straight_residual;
  if (!plan.rate_tail_excluded) {
    out.message = "the straight rolling reaches the target within the margin (delta0 " +
                  std::to_string(plan.straight_residual) + " rad): no rate bound, parameter space is unbounded";
    return out;
  }
  RunPieces(solved, target, plan.pieces, options, &out);
  Conclude(solved, &out);
  out.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string IsoparallelCertificate::BriefReport() const {
  std::ostringstream os;
  os << "Isoparallel certificate: " << ToString(status);
  if (status == IsoparallelCertificateStatus::kComplete || status == IsoparallelCertificateStatus::kIncomplete ||
      status == IsoparallelCertificateStatus::kInterrupted)
    os << std::setprecision(10) << ", length cap " << length_cap << ", " << solutions.size() << " solution(s) proved, "
       << MissedBySolver() << " missed by the solver, " << boxes << " boxes in " << pieces.size() << " pieces"
       << std::setprecision(4) << ", " << cpu_seconds << " s CPU, " << time_seconds << " s";
  return os.str();
}

std::string IsoparallelCertificate::FullReport() const {
  std::ostringstream os;
  os << BriefReport() << "\n";
  if (!message.empty()) os << "  " << message << "\n";
  for (const CertifiedSolution& s : solutions)
    os << std::setprecision(10) << "  " << ToString(s.regime) << " rate " << s.rate << " k " << s.modulus << " phase "
       << s.phase << " length " << s.length
       << (s.solver_index >= 0 ? " (the solver's #" + std::to_string(s.solver_index + 1) + ")"
                               : " (missed by the solver)")
       << "\n";
  for (const IsoparallelCertificatePiece& p : pieces)
    os << std::setprecision(4) << "  " << (p.closed ? "closed " : "OPEN   ") << p.name << ": " << p.boxes << " boxes, "
       << p.cpu_seconds << " s CPU\n";
  return os.str();
}

}  // namespace plateball
