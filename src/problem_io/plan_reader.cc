// The "plan" section: the path (path_reader.cc), its partition into impulse steps, the energy
// changes at given impulses and the n of a convergence study.
#include "plateball/limits.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {
PlanTask PlanReader::Plan(const json& j, const std::string& path) const {
  Object(j, path, {"path", "partition", "energy_changes", "converge_n"});
  PlanTask t;
  t.path = PathReader(*this).Path(Require(j, path, "path"), Join(path, "path"), 0);
  if (const json* v = Find(j, "partition")) t.partition = Partition(*v, Join(path, "partition"));
  if (const json* v = Find(j, "energy_changes")) t.energy_changes = EnergyChanges(*v, Join(path, "energy_changes"));
  if (const json* v = Find(j, "converge_n")) {
    const std::string cp = Join(path, "converge_n");
    Array(*v, cp, 0, limits::kMaxListLength);
    for (std::size_t i = 0; i < v->size(); ++i)
      t.converge_n.push_back(static_cast<int>(Integer((*v)[i], Index(cp, i), 1, kMaxPartitionCount)));
  }
  return t;
}

PartitionSpec PlanReader::Partition(const json& j, const std::string& path) const {
  Object(j, path, {"type", "n", "taus"});
  std::string type = "uniform_parameter";
  if (const json* v = Find(j, "type")) type = String(*v, Join(path, "type"));
  if (type == "explicit") {
    if (const json* v = Find(j, "n")) Fail(Join(path, "n"), *v, "not allowed for an explicit partition (n = taus - 1)");
    const std::string tp = Join(path, "taus");
    const json& taus = Array(Require(j, path, "taus"), tp, 2, kMaxPartitionCount + 1);
    ExplicitTaus s;
    for (std::size_t i = 0; i < taus.size(); ++i) {
      s.taus.push_back(Number(taus[i], Index(tp, i)));
      if (i > 0 && !(s.taus[i] > s.taus[i - 1])) Fail(Index(tp, i), taus[i], "taus must be strictly increasing");
    }
    return s;
  }
  if (type != "uniform_parameter" && type != "uniform_arc_length")
    Fail(Join(path, "type"),
         j["type"],
         "unknown partition type (one of uniform_parameter, uniform_arc_length, explicit)");
  if (const json* v = Find(j, "taus")) Fail(Join(path, "taus"), *v, "only allowed for an explicit partition");
  int n = UniformParameter{}.n;
  if (const json* v = Find(j, "n")) n = static_cast<int>(Integer(*v, Join(path, "n"), 1, kMaxPartitionCount));
  if (type == "uniform_parameter") return UniformParameter{n};
  return UniformArcLength{n};
}

std::vector<EnergyChangeSpec> PlanReader::EnergyChanges(const json& v, const std::string& path) const {
  std::vector<EnergyChangeSpec> out;
  Array(v, path, 0, limits::kMaxListLength);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string e = Index(path, i);
    const json& c = v[i];
    Object(c, e, {"index", "factor"});
    EnergyChangeSpec spec;
    spec.index = static_cast<int>(Integer(Require(c, e, "index"), Join(e, "index"), 0, kMaxPartitionCount));
    spec.factor = Positive(Require(c, e, "factor"), Join(e, "factor"));
    out.push_back(spec);
  }
  return out;
}

}  // namespace plateball::internal::problem_io
