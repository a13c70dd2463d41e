// Quickstart: the log lobe with its exact normalization, as a BRDF and as a bare lobe.
#include <cstdio>

#include <specula/catalogue/catalogue.h>
#include <specula/lobes/log.h>

int main() {
  const specula::Model model = specula::make_model("log-normalized", {{"n", 20}});
  const specula::Vec3 N{0, 0, 1}, L{0.6, 0, 0.8}, V{-0.48, 0.36, 0.8};
  std::printf("k(n = 20)   = %.6f\n", model.coef());
  std::printf("f(N, L, V)  = %.6f\n", model(N, L, V));
  std::printf("F_log(0.95) = %.6f\n", specula::lobes::Log<float>{20}(0.95f));
}
