// The identity of the code that generates and bakes trees: a hash over the contents of the
// generator, scene, renderer, Vulkan, bake and shader sources and the toolchain, computed at
// build time by cmake/build_identity.cmake. Two binaries with the same identity make the same
// species cache entries from the same inputs on the same device.
#pragma once

namespace forest {

const char* bake_build_identity();  // 32 hex digits
int bake_build_sources();           // how many source files it covers

}  // namespace forest
