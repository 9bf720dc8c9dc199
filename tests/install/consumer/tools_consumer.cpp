#include <cmath>
#include <cstdio>
#include <sphys/tools/mass_properties.h>
#include <sphys/tools/primitives.h>

int main() {
  const auto box = sphys::tools::make_box({1, 2, 3});
  const double volume = sphys::tools::compute_mass_properties(box).volume;
  const bool ok = std::abs(volume - 6.0) < 1e-12;
  std::printf("tools consumer: box volume %g\n", volume);
  return ok ? 0 : 1;
}
