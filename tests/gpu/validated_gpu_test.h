// The fixture of the GPU tests: a Vulkan context with the Khronos validation layer on, and
// a test that fails if the layer reported any warning or error while it ran. Tests that
// need another context (synchronization validation) make it with the same two helpers.
#pragma once
#include <gtest/gtest.h>

#include "engine/vk/context.h"

namespace forest {

// The validation layer on; with `synchronization`, its synchronization validation too.
inline vk::ContextOptions validation_options(bool synchronization = false) {
  vk::ContextOptions options;
  options.validation = true;
  options.synchronization_validation = synchronization;
  return options;
}

// Destroys the context; the test fails if the layer reported anything while it lived.
inline void destroy_validated_context(vk::Context& ctx) {
  vk::destroy_context(ctx);
  EXPECT_EQ(ctx.validation_messages.load(), 0u) << "last: " << ctx.last_validation_message;
}

class ValidatedGpuTest : public ::testing::Test {
 protected:
  void SetUp() override { vk::create_context(ctx_, validation_options()); }
  void TearDown() override { destroy_validated_context(ctx_); }
  vk::Context ctx_;
};

}  // namespace forest
