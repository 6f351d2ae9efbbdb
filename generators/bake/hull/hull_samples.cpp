#include "generators/bake/hull/hull_samples.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "generators/core/rng.h"

namespace forest {

SurfaceSamples spread_samples(const Mesh& mesh, uint32_t count, uint64_t seed,
                              uint32_t candidates_per_sample) {
  SurfaceSamples out;
  const size_t ntri = mesh.indices.size() / 3;
  if (ntri == 0 || count == 0) return out;

  auto corner = [&](size_t t, int k) -> const Vertex& { return mesh.vertices[mesh.indices[3 * t + k]]; };
  std::vector<double> cumulative(ntri);
  double total = 0.0;
  for (size_t t = 0; t < ntri; ++t) {
    glm::dvec3 a(corner(t, 0).position), b(corner(t, 1).position), c(corner(t, 2).position);
    total += 0.5 * glm::length(glm::cross(b - a, c - a));
    cumulative[t] = total;
  }
  if (!(total > 0.0)) return out;

  // Candidates: uniform by area (triangle by inverse CDF, point by the square-root map).
  const size_t ncand = size_t(count) * std::max<uint32_t>(1, candidates_per_sample);
  std::vector<glm::vec3> cand(ncand), cand_normal(ncand);
  Rng rng(seed, 0x5A4D504Cull);
  for (size_t i = 0; i < ncand; ++i) {
    double u = rng.uniform() * total;
    size_t t = size_t(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
    t = std::min(t, ntri - 1);
    double s = std::sqrt(rng.uniform()), r = rng.uniform();
    glm::dvec3 w(1.0 - s, s * (1.0 - r), s * r);
    glm::dvec3 p = w.x * glm::dvec3(corner(t, 0).position) + w.y * glm::dvec3(corner(t, 1).position) +
                   w.z * glm::dvec3(corner(t, 2).position);
    glm::dvec3 n = w.x * glm::dvec3(corner(t, 0).normal) + w.y * glm::dvec3(corner(t, 1).normal) +
                   w.z * glm::dvec3(corner(t, 2).normal);
    if (!(glm::dot(n, n) > 1e-24))
      n = glm::cross(glm::dvec3(corner(t, 1).position - corner(t, 0).position),
                     glm::dvec3(corner(t, 2).position - corner(t, 0).position));
    cand[i] = glm::vec3(p);
    cand_normal[i] = glm::dot(n, n) > 0.0 ? glm::vec3(glm::normalize(n)) : glm::vec3(0, 1, 0);
  }

  // Farthest-point selection (Gonzalez): each new sample is the candidate farthest from all
  // chosen ones, which spreads them like a Poisson-disc set of the largest possible radius.
  std::vector<float> dist(ncand, std::numeric_limits<float>::max());
  size_t pick = 0;  // candidates are random already: the first one is a random start
  const size_t n = std::min<size_t>(count, ncand);
  for (size_t s = 0; s < n; ++s) {
    out.points.push_back(cand[pick]);
    out.normals.push_back(cand_normal[pick]);
    size_t next = 0;
    float far = -1.0f;
    for (size_t i = 0; i < ncand; ++i) {
      glm::vec3 d = cand[i] - cand[pick];
      dist[i] = std::min(dist[i], glm::dot(d, d));
      if (dist[i] > far) far = dist[i], next = i;
    }
    pick = next;
  }
  return out;
}

}  // namespace forest
