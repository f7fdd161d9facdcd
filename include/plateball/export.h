// PLATEBALL_EXPORT: the visibility of the library's public API.
//
// The library is compiled with hidden default visibility (-fvisibility=hidden
// -fvisibility-inlines-hidden), so the shared library exports only what its public headers
// declare, not the Eigen, Boost and nlohmann-json instantiations it uses inside. Every public
// header opens its namespace as
//     namespace plateball PLATEBALL_EXPORT {
// (GCC's namespace attribute form: the attribute follows the name and precedes the body), which
// gives default visibility to every function, class and variable first declared in that body.
// Declarations in src/ headers (plateball::internal) stay hidden.
//
// The macro needs no definition from the consumer: it is the same when building and when using
// the library, shared or static.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define PLATEBALL_EXPORT __attribute__((visibility("default")))
#else
#define PLATEBALL_EXPORT
#endif
