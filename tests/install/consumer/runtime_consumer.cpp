#include <cstdio>
#include <sphys/math.h>

int main() {
  sphys::Aabb box = sphys::Aabb::around_sphere(sphys::Vec3(0, 1, 0), 0.5f);
  const bool ok = box.overlaps(sphys::Aabb::around_sphere(sphys::Vec3(0, 1.9f, 0), 0.5f));
  std::printf("runtime consumer: %s\n", ok ? "ok" : "wrong");
  return ok ? 0 : 1;
}
