// The web assets of `plateball view`, embedded at build time by web/embed_assets.cmake: the page
// template (web/view.html), its script (web/rig_layers.js then web/view.js), three.js from the npm registry
// (web/package.json, node_modules/three/build/three.module.min.js, its ES-module export turned into a `THREE` object)
// and the result-field mapping (web/result_fields.json).
#pragma once

namespace plateball::tools::view {

extern const char* const kViewTemplate;
extern const char* const kViewScript;
extern const char* const kThreeScript;
extern const char* const kThreeVersion;
extern const char* const kResultFields;

}  // namespace plateball::tools::view
