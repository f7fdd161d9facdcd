// Text of values for the problem reader's and writer's messages: numbers in their shortest exact
// form, JSON values bounded in depth and length whatever the input.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace plateball::internal::problem_io {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

/// A double as the shortest text that reads back to it ("nan", "inf", integral values without ".0").
std::string NumberText(double v);
/// A compact rendering of a JSON value of at most about 160 characters.
std::string ValueText(const json& j);
/// "[a, b, ...]" of n doubles.
std::string VectorText(const double* v, int n);

}  // namespace plateball::internal::problem_io
