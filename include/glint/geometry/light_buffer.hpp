#pragma once
// A light buffer (Haines and Greenberg, "The Light Buffer: A Shadow-Testing Accelerator", IEEE
// CG&A 1986): around a point light, a cube of directions divided into cells, each listing the
// spheres that may lie between the light and a point seen from it in that cell's directions.
// A shadow ray toward the light is tested against its cell's spheres only, instead of every
// sphere of the scene: in a room of 40 spheres, a cell lists a handful.
//
// The answer must be the one the full scan gives, bit for bit (ray_batch.hpp), so the cells are
// conservative and the spheres they list are tested by the scan's own kernel
// (test_lanes). A cell lists every sphere that the kernel could find a hit on for a ray
// of that cell, with margins worked out below (see LightBuffer::Margins); a ray that does not
// end at the light to within those margins (LightBuffer::ends_here) is left to the full scan.
// Only the spheres of the linear set (small scenes) are listed: a cell is two bytes, a bit for
// each group of kBatchWidth spheres it needs (so up to 128 spheres).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

#ifdef GLINT_AVX2
namespace glint::inline GLINT_ISA_NAMESPACE {

class LightBuffer {
 public:
  /// Cells along an edge of a face of the cube of directions.
  static constexpr int kCellsPerEdge = 32;
  static constexpr int kCells = 6 * kCellsPerEdge * kCellsPerEdge;
  /// The spheres that one bit of a cell stands for: those the kernel tests at once.
  static constexpr std::size_t kGroupSize = kBatchWidth;
  /// The groups a cell lists, a bit each.
  using CellGroups = std::uint16_t;
  /// The most spheres a buffer lists: a group for each bit of a cell.
  static constexpr std::size_t kMaxSpheres =
      std::size_t(std::numeric_limits<CellGroups>::digits) * kGroupSize;

  /// The cell of direction `w` (not zero): the face of its largest coordinate in magnitude
  /// (x, y, z: faces 0-1, 2-3, 4-5, the second for a negative one, the first on ties), and
  /// on it the square of the other two coordinates divided by that one. NaN goes to cell 0.
  static int cell_of(const Vec3& w) { return cell_lanes<Lanes1>(w.x, w.y, w.z); }

  /// cell_of for the direction (x, y, z) of each lane, in registers of L (simd.hpp).
  template <class L>
  static typename L::I cell_lanes(typename L::F x, typename L::F y, typename L::F z) {
    using F = typename L::F;
    using I = typename L::I;
    using M = typename L::M;
    const F ax = L::abs(x), ay = L::abs(y), az = L::abs(z);
    const M x_major = L::both(L::greater_equal(ax, ay), L::greater_equal(ax, az));
    const M y_major = L::and_not(L::greater_equal(ay, az), x_major);
    // The major coordinate and the two after it, cyclically: (x; y, z), (y; z, x), (z; x, y).
    const F major = L::select(x_major, x, L::select(y_major, y, z));
    const F first = L::select(x_major, y, L::select(y_major, z, x));
    const F second = L::select(x_major, z, L::select(y_major, x, y));
    const F major_size = L::abs(major);
    const I axis_face =
        L::select(x_major, L::splat(0), L::select(y_major, L::splat(2), L::splat(4)));
    const I face = L::add(axis_face, L::keep(L::less(major, L::zero()), L::splat(1)));
    const I u = square_index<L>(L::div(first, major_size));
    const I v = square_index<L>(L::div(second, major_size));
    const I edge = L::splat(kCellsPerEdge);
    return L::add(L::mul(L::add(L::mul(face, edge), u), edge), v);
  }

  LightBuffer() = default;

  /// The buffer of a light at `light` over `spheres` (at most kMaxSpheres; their columns are
  /// copied, grouped by direction from the light).
  LightBuffer(const Vec3& light, const avx2::SphereColumns& spheres) : light_(light) {
    const std::size_t count = spheres.size;
    // Where the spheres reach from the light, which bounds the rays that the margins cover.
    double reach = 0.0;
    for (std::size_t i = 0; i < count; ++i)
      reach = std::max(reach, distance_to(spheres, i) + std::sqrt(double(spheres.r2[i])));
    const Margins margins(light, reach);
    max_length_ = float(margins.max_length);
    endpoint_tolerance2_ = float(margins.endpoint_tolerance * margins.endpoint_tolerance);

    // Spheres in the order of their cell seen from the light, so that neighbouring cells'
    // spheres share groups.
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::vector<int> key(count);
    for (std::size_t i = 0; i < count; ++i)
      key[i] = cell_key(Vec3(spheres.cx[i], spheres.cy[i], spheres.cz[i]) - light);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
    const std::size_t padded = (count + kGroupSize - 1) / kGroupSize * kGroupSize;
    cx_.resize(padded, 0.0f);
    cy_.resize(padded, 0.0f);
    cz_.resize(padded, 0.0f);
    r2_.resize(padded, -1.0f);  // as SphereSet's padding: no ray meets it
    ids_.resize(padded, kNoSphere);
    for (std::size_t slot = 0; slot < count; ++slot) {
      const std::size_t i = order[slot];
      cx_[slot] = spheres.cx[i];
      cy_[slot] = spheres.cy[i];
      cz_[slot] = spheres.cz[i];
      r2_[slot] = spheres.r2[i];
      ids_[slot] = spheres.id[i];
    }
    count_ = count;

    cell_groups_.assign(std::size_t(kCells), 0);
    const std::vector<CellCone>& cells = cell_cones();
    for (std::size_t slot = 0; slot < count; ++slot) {
      const auto group = CellGroups(1u << (slot / kGroupSize));
      const double distance = distance_to(columns(), slot);
      const double sphere_radius = std::sqrt(double(r2_[slot]));
      const double radius = sphere_radius + margins.kernel_error(sphere_radius);
      if (distance - radius <= margins.near_light) {
        // Near or around the light: in every direction.
        for (CellGroups& groups : cell_groups_)
          groups |= group;
        continue;
      }
      const glm::dvec3 axis =
          glm::dvec3(double(cx_[slot]) - double(light.x), double(cy_[slot]) - double(light.y),
                     double(cz_[slot]) - double(light.z)) /
          distance;
      // The sphere's cone and a cell's overlap when their axes are at most the sum a + b of
      // their half angles apart: cos(a + b) = cos a cos b - sin a sin b.
      const double half_angle = std::asin(radius / distance) + margins.direction_error;
      const double cos_half = std::cos(half_angle), sin_half = std::sin(half_angle);
      for (std::size_t c = 0; c < cells.size(); ++c) {
        const bool overlap = half_angle + cells[c].half_angle >= kPi ||
                             glm::dot(axis, cells[c].axis) >=
                                 cos_half * cells[c].cos_half - sin_half * cells[c].sin_half;
        if (overlap) cell_groups_[c] |= group;
      }
    }
  }

  const Vec3& light() const { return light_; }

  /// The lanes of `lanes` whose ray ends at the light: t_min at least 0, a direction of length
  /// 0.9 to 1.1 and
  /// t_max no more than the length the margins cover, and origin + t_max direction within the
  /// endpoint tolerance of the light (a shadow ray of PathContext::light_rays, to
  /// rounding). NaN in a lane fails every comparison, so that lane is not one of them.
  unsigned ends_here(const avx2::RayLanes& rays, __m256 t_max, unsigned lanes) const {
    const __m256 ex =
        _mm256_sub_ps(_mm256_fmadd_ps(t_max, rays.dx, rays.ox), _mm256_set1_ps(light_.x));
    const __m256 ey =
        _mm256_sub_ps(_mm256_fmadd_ps(t_max, rays.dy, rays.oy), _mm256_set1_ps(light_.y));
    const __m256 ez =
        _mm256_sub_ps(_mm256_fmadd_ps(t_max, rays.dz, rays.oz), _mm256_set1_ps(light_.z));
    const __m256 miss2 = _mm256_fmadd_ps(ex, ex, _mm256_fmadd_ps(ey, ey, _mm256_mul_ps(ez, ez)));
    const __m256 length2 = _mm256_fmadd_ps(
        rays.dx, rays.dx, _mm256_fmadd_ps(rays.dy, rays.dy, _mm256_mul_ps(rays.dz, rays.dz)));
    const __m256 ends = _mm256_and_ps(
        _mm256_and_ps(_mm256_cmp_ps(miss2, _mm256_set1_ps(endpoint_tolerance2_), _CMP_LE_OQ),
                      _mm256_cmp_ps(t_max, _mm256_set1_ps(max_length_), _CMP_LE_OQ)),
        _mm256_and_ps(_mm256_cmp_ps(length2, _mm256_set1_ps(0.81f), _CMP_GE_OQ),
                      _mm256_cmp_ps(length2, _mm256_set1_ps(1.21f), _CMP_LE_OQ)));
    const __m256 forward = _mm256_cmp_ps(rays.t_min, _mm256_setzero_ps(), _CMP_GE_OQ);
    return unsigned(_mm256_movemask_ps(_mm256_and_ps(ends, forward))) & lanes;
  }

  /// cell_of(-direction) in each lane: the cell of the way back from the light to the origin.
  static __m256i cells(const avx2::RayLanes& rays) {
    using L = avx2::Lanes8;
    return cell_lanes<L>(L::negate(rays.dx), L::negate(rays.dy), L::negate(rays.dz));
  }

  /// Whether a sphere of the buffer blocks `ray` (one that ends here, in cell `cell`): exactly
  /// the full scan's verdict on the buffer's spheres (see the margins).
  bool blocks(const Ray& ray, int cell) const {
    const avx2::RayLanes lanes(ray);
    avx2::HitLanes bound(hit_to_beat(ray, SphereHit{}));
    const avx2::SphereColumns spheres = columns();
    for (unsigned groups = cell_groups_[std::size_t(cell)]; groups != 0; groups &= groups - 1) {
      const std::size_t base = std::size_t(std::countr_zero(groups)) * kGroupSize;
      if (avx2::test_8_spheres(lanes, spheres, base, bound)) return true;
    }
    return false;
  }

  /// The groups of spheres (bit g: columns() g kGroupSize .. (g + 1) kGroupSize - 1) listed in
  /// a cell.
  unsigned groups(int cell) const { return cell_groups_[std::size_t(cell)]; }

  avx2::SphereColumns columns() const {
    return {cx_.data(), cy_.data(), cz_.data(), r2_.data(), ids_.data(), count_};
  }
  float max_length() const { return max_length_; }

 private:
  static constexpr double kPi = 3.14159265358979323846;

  /// The margins, all in double, as multiples of a scale s = 2 |light| + 6 reach (reach: how
  /// far the spheres extend from the light), which bounds |origin| + |light| and
  /// |origin - centre| for every ray the buffer takes (ends_here: no longer than 4 reach, a
  /// direction of length at most 1.1, ending within the tolerance of the light).
  ///  - The kernel: where it finds a hit at t, the exact point origin + t direction lies within
  ///    a few ulps of |f| + r of the sphere (f = origin - centre; the discriminant's
  ///    perpendicular form, ray_sphere.hpp). The worst of two million rays aimed at spheres'
  ///    silhouettes (radii 1e-3 to 300, |f| up to 500) was 2^-21.6 (|f| + r); each sphere is
  ///    widened by 2^-15 (s + r), a hundred times that.
  ///  - The endpoint: a shadow ray of PathContext::light_rays ends within 2^-23.4 (|origin| +
  ///    |light|) of the light (the worst of five million); ends_here accepts 2^-18 s. A point
  ///    of the ray at least rho from the light then lies within asin(2^-18 s / rho) of the
  ///    direction back along the ray: spheres that come within rho = 2^-8 s of the light
  ///    (widened) are listed in every cell, and the others' cones are widened by 2^-9 radians
  ///    (twice that angle), plus 2^-16 for the rounding of a cell lookup near a cell's border.
  struct Margins {
    Margins(const Vec3& light, double reach) {
      const double light_norm = glm::length(glm::dvec3(light));
      scale = 2.0 * light_norm + 6.0 * reach;
      max_length = 4.0 * reach;
      endpoint_tolerance = std::ldexp(scale, -18);
      near_light = std::ldexp(scale, -8);
      direction_error = std::ldexp(1.0, -9) + std::ldexp(1.0, -16);
    }
    double kernel_error(double radius) const { return std::ldexp(scale + radius, -15); }

    double scale, max_length, endpoint_tolerance, near_light, direction_error;
  };

  /// A cell's directions: within half_angle of the unit axis.
  struct CellCone {
    glm::dvec3 axis;
    double half_angle, cos_half, sin_half;
  };

  /// The direction of point (u, v) of face `face` of the cube (cell_of's inverse).
  static glm::dvec3 face_point(int face, double u, double v) {
    const int axis = face / 2;
    const double major = face % 2 == 0 ? 1.0 : -1.0;
    double c[3];
    c[axis] = major;
    c[(axis + 1) % 3] = u;
    c[(axis + 2) % 3] = v;
    return glm::normalize(glm::dvec3(c[0], c[1], c[2]));
  }

  /// The cones around the cells (the same for every buffer, made once): the spherical
  /// square's farthest points from its centre are its corners.
  static const std::vector<CellCone>& cell_cones() {
    static const std::vector<CellCone> cones = make_cell_cones();
    return cones;
  }
  static std::vector<CellCone> make_cell_cones() {
    std::vector<CellCone> cones;
    cones.reserve(std::size_t(kCells));
    const double step = 2.0 / kCellsPerEdge;
    for (int face = 0; face < 6; ++face)
      for (int i = 0; i < kCellsPerEdge; ++i)
        for (int j = 0; j < kCellsPerEdge; ++j) {
          const double u0 = -1.0 + step * i, v0 = -1.0 + step * j;
          const glm::dvec3 axis = face_point(face, u0 + 0.5 * step, v0 + 0.5 * step);
          double half_angle = 0.0;
          for (const double u : {u0, u0 + step})
            for (const double v : {v0, v0 + step})
              half_angle = std::max(
                  half_angle,
                  std::acos(std::clamp(glm::dot(axis, face_point(face, u, v)), -1.0, 1.0)));
          cones.push_back({axis, half_angle, std::cos(half_angle), std::sin(half_angle)});
        }
    return cones;
  }

  /// The row or column of a face's cells at a coordinate in [-1, 1] of it, in each lane; NaN
  /// goes to 0 (the maximum is taken first, and gives its second operand for NaN).
  template <class L>
  static typename L::I square_index(typename L::F coordinate) {
    const typename L::F scaled =
        L::mul(L::add(coordinate, L::splat(1.0f)), L::splat(0.5f * kCellsPerEdge));
    return L::truncate(L::min(L::max(scaled, L::zero()), L::splat(float(kCellsPerEdge - 1))));
  }

  /// Orders spheres by face, then along a Z-order curve of the face's cells.
  static int cell_key(const Vec3& direction) {
    const int cell = cell_of(direction);
    const int face = cell / (kCellsPerEdge * kCellsPerEdge);
    const int i = cell / kCellsPerEdge % kCellsPerEdge, j = cell % kCellsPerEdge;
    int morton = 0;
    for (int bit = 0; (1 << bit) < kCellsPerEdge; ++bit)
      morton |= ((i >> bit & 1) << (2 * bit + 1)) | ((j >> bit & 1) << (2 * bit));
    return face * kCellsPerEdge * kCellsPerEdge + morton;
  }

  double distance_to(const avx2::SphereColumns& spheres, std::size_t i) const {
    return glm::length(glm::dvec3(double(spheres.cx[i]) - double(light_.x),
                                  double(spheres.cy[i]) - double(light_.y),
                                  double(spheres.cz[i]) - double(light_.z)));
  }

  Vec3 light_{0.0f};
  float max_length_ = 0.0f;
  float endpoint_tolerance2_ = 0.0f;
  std::vector<CellGroups> cell_groups_;
  detail::AlignedArray<float> cx_, cy_, cz_, r2_;
  detail::AlignedArray<std::uint32_t> ids_;
  std::size_t count_ = 0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
#endif
