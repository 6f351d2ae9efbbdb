// The fixture of the GPU tests: a Vulkan context with the Khronos validation layer on, and
// a test that fails if the layer reported any warning or error while it ran.
#pragma once
#include <gtest/gtest.h>

#include "engine/vk/context.h"

namespace forest {

class ValidatedGpuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    vk::ContextOptions options;
    options.validation = true;
    vk::create_context(ctx_, options);
  }
  void TearDown() override {
    vk::destroy_context(ctx_);
    EXPECT_EQ(ctx_.validation_messages.load(), 0u) << "last: " << ctx_.last_validation_message;
  }
  vk::Context ctx_;
};

}  // namespace forest
