// Prints the Highway targets this machine runs, as Highway's bit mask (cmake/hwy_targets.cmake).
#include <hwy/targets.h>

#include <cstdio>

int main() { std::printf("%lld", static_cast<long long>(hwy::SupportedTargets())); }
