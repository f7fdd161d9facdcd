// The top level of a problem file: its keys, and each section by its reader (section_readers.h).
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {

Problem DocumentReader::Document(const json& root) const {
  if (!root.is_object()) Fail("(document)", root, "a problem file must be a JSON object");
  Object(root,
         "",
         {"name",
          "description",
          "seed",
          "integration",
          "ball",
          "initial",
          "simulate",
          "reach",
          "plan",
          "isoparallel",
          "steer",
          "rig",
          "expected"});
  Problem p;
  p.source = source();
  if (const json* v = Find(root, "name")) p.name = String(*v, "name");
  if (const json* v = Find(root, "description")) p.description = String(*v, "description");
  if (const json* v = Find(root, "seed")) p.seed = Seed(*v, "seed");
  if (const json* v = Find(root, "integration")) StartStateReader(*this).Integration(*v, "integration", &p.integration);
  StartStateReader(*this).Ball(Require(root, "", "ball"), "ball", &p);
  StartStateReader(*this).Initial(Require(root, "", "initial"), "initial", &p);
  if (const json* v = Find(root, "simulate")) p.simulate = RunSectionsReader(*this).Simulate(*v, "simulate");
  if (const json* v = Find(root, "reach")) p.reach = RunSectionsReader(*this).Reach(*v, "reach");
  if (const json* v = Find(root, "plan")) p.plan = PlanReader(*this).Plan(*v, "plan");
  if (const json* v = Find(root, "isoparallel"))
    p.isoparallel = IsoparallelReader(*this).Isoparallel(*v, "isoparallel");
  if (const json* v = Find(root, "steer")) p.steer = SteerReader(*this).Steer(*v, "steer");
  if (const json* v = Find(root, "rig")) p.rig = RigReader(*this).Rig(*v, "rig", p.physical);
  if (const json* v = Find(root, "expected")) p.expected = RunSectionsReader(*this).Expected(*v, "expected");
  return p;
}

}  // namespace plateball::internal::problem_io
