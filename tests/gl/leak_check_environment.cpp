// LeakSanitizer's check at a quiet moment: after the last test, while Mesa's llvmpipe threads are
// idle. Left to run at exit, the check stops the world while those threads are being torn down,
// and its tracer sometimes crashes on one that is exiting ("Tracer caught signal 11") after every
// test has passed. __lsan_do_leak_check runs the same check now, exits non-zero on a leak exactly
// as the end-of-process check would, and turns that one off. Without AddressSanitizer it is a no-op.
#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace {

class LeakCheckBeforeExit : public ::testing::Environment {
 public:
  void TearDown() override {
#if defined(__SANITIZE_ADDRESS__)
    __lsan_do_leak_check();
#endif
  }
};

const auto* const registered = ::testing::AddGlobalTestEnvironment(new LeakCheckBeforeExit);

}  // namespace
