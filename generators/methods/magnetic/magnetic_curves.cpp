#include "generators/methods/magnetic/magnetic_curves.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "generators/core/input_error.h"
#include "generators/core/rng.h"

namespace forest {

namespace {

double lattice(int64_t x, int64_t y, int64_t z, uint64_t seed) {
  uint64_t h = hash64(uint64_t(x) ^ (seed * 0x9E3779B97F4A7C15ull), uint64_t(y), uint64_t(z));
  return double(h >> 11) * 0x1.0p-52 - 1.0;  // [-1, 1)
}

double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

}  // namespace

double charge_at(const Charge& c, double t) {
  double q = 0.0;
  switch (c.profile) {
    case ChargeProfile::Constant:
      q = c.q0;
      break;
    case ChargeProfile::Power:
      q = c.q0 * std::pow(t + 1.0, -c.alpha);
      break;
    case ChargeProfile::Spiral:
      q = c.q0 * std::pow(std::max(c.T - t, 1e-3), -c.alpha);
      break;
    case ChargeProfile::Triangle: {
      double ph = std::fmod(t / c.period, 1.0);
      q = c.mean + c.amplitude * (ph < 0.5 ? 4.0 * ph - 1.0 : 3.0 - 4.0 * ph) * 0.5;
      break;
    }
    case ChargeProfile::Square:
      q = c.mean + (std::fmod(t / c.period, 1.0) < 0.5 ? 0.5 : -0.5) * c.amplitude;
      break;
  }
  return c.sign * q;
}

double value_noise(double x, double y, double z, uint64_t seed) {
  double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  int64_t ix = int64_t(fx), iy = int64_t(fy), iz = int64_t(fz);
  double tx = smooth(x - fx), ty = smooth(y - fy), tz = smooth(z - fz);
  double v = 0.0;
  for (int c = 0; c < 8; ++c) {
    int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
    v += w * lattice(ix + dx, iy + dy, iz + dz, seed);
  }
  return v;
}

glm::dvec3 field_at(const MagneticField& f, glm::dvec3 p) {
  if (!f.three_d) {
    double bz = f.b0;
    if (f.noise > 0.0) {
      double n = value_noise(p.x / f.noise_scale, p.y / f.noise_scale, 0.0, f.seed);
      bz = f.b0 * ((1.0 - f.noise) + f.noise * 0.5 * (1.0 + n));
    }
    return {0.0, 0.0, bz};
  }
  glm::dvec3 q = p / f.noise_scale;
  glm::dvec3 b(value_noise(q.x, q.y, q.z, f.seed), f.tilt, value_noise(q.x, q.y, q.z, f.seed + 1));
  double len = glm::length(b);
  return len > 1e-9 ? f.b0 * b / len : glm::dvec3(0.0, f.b0, 0.0);
}

void lorentz_step(Particle& p, double q, glm::dvec3 B, double dt) {
  double speed = glm::length(p.velocity);
  glm::dvec3 a = (q / p.mass) * glm::cross(p.velocity, B);
  glm::dvec3 v = p.velocity + a * dt;
  double len = glm::length(v);
  if (len > 0.0) p.velocity = v * (speed / len);
  p.position += p.velocity * dt;
}

std::vector<glm::dvec3> trace_particle(Particle p, const Charge& c, const MagneticField& f,
                                       double dt, int steps) {
  std::vector<glm::dvec3> out{p.position};
  for (int i = 0; i < steps; ++i) {
    lorentz_step(p, charge_at(c, double(i) * dt), field_at(f, p.position), dt);
    out.push_back(p.position);
  }
  return out;
}

size_t MagneticResult::cell_of(glm::dvec3 p) const {
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(std::floor(p[a] / cell)), 0, dims[a] - 1);
  return (size_t(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
}

bool inside_dome(const SpaceFillParams& P, bool three_d, glm::dvec3 p) {
  const double x = (p.x - 0.5 * P.size.x) / (0.5 * P.size.x), y = p.y / P.size.y;
  const double z = three_d ? (p.z - 0.5 * P.size.z) / (0.5 * P.size.z) : 0.0;
  return x * x + y * y + z * z <= 1.0;
}

MagneticResult grow_magnetic(const SpaceFillParams& P, const MagneticField& field, uint64_t seed) {
  MagneticResult R;
  R.cell = P.cell;
  const bool three_d = field.three_d;
  double cells = 1.0;
  for (int a = 0; a < (three_d ? 3 : 2); ++a) {
    R.dims[a] = std::max(1, int(std::ceil(P.size[a] / P.cell)));
    cells *= R.dims[a];
  }
  if (cells > double(1 << 26)) throw InputError("magnetic: domain / cell gives too many grid cells");
  R.owner.assign(size_t(cells), -1);
  auto inside = [&](glm::dvec3 p) {
    return p.x >= 0 && p.y >= 0 && p.x <= P.size.x && p.y <= P.size.y &&
           (!three_d || (p.z >= 0 && p.z <= P.size.z)) && (P.domain == Domain::Box || inside_dome(P, three_d, p));
  };
  // Traces one particle; claims cells as it goes, releases them on a crossing.
  std::vector<size_t> claimed;
  auto try_curve = [&](int32_t id, int32_t parent, glm::dvec3 start, glm::dvec3 dir, double sign,
                       const SpiralPair& pair, MagneticCurve& out) -> bool {
    Charge c = P.charge;
    if (id == 0) c.q0 = P.trunk_q0;
    c.T = pair.T;
    c.alpha = pair.alpha;
    c.sign = sign;
    Particle p;
    p.position = start;
    p.velocity = glm::normalize(dir) * P.speed;
    p.mass = P.mass;
    out.points.assign(1, start);
    claimed.clear();
    size_t last = R.cell_of(start);
    const int steps = int(pair.T / P.dt);
    for (int i = 0; i < steps; ++i) {
      lorentz_step(p, charge_at(c, double(i) * P.dt), field_at(field, p.position), P.dt);
      if (!three_d) p.position.z = start.z;
      if (!inside(p.position)) break;  // the border ends a curve; it is kept
      size_t cell = R.cell_of(p.position);
      if (cell != last) {
        int32_t o = R.owner[cell];
        if (o < 0) {
          R.owner[cell] = id;
          claimed.push_back(cell);
        } else if (o != id && o != parent) {
          for (size_t k : claimed) R.owner[k] = -1;  // crossing: undo, caller retries
          return false;
        }
        last = cell;
      }
      out.points.push_back(p.position);
    }
    return out.points.size() >= 2;
  };

  Rng rng(seed, 21);
  MagneticCurve first;
  glm::dvec3 start(0.5 * P.size.x, 0.0, three_d ? 0.5 * P.size.z : 0.0);
  double sign0 = rng.uniform() < 0.5 ? -1.0 : 1.0;
  for (size_t k = 0; k < P.pairs.size(); ++k)
    if (try_curve(0, -1, start, glm::dvec3(0, 1, 0), sign0, P.pairs[k], first)) {
      first.pair = int(k);
      R.curves.push_back(std::move(first));
      break;
    }
  // Breadth first: release children at even arc-length intervals along every curve.
  for (size_t ci = 0; ci < R.curves.size() && int(R.curves.size()) < P.max_curves; ++ci) {
    if (int(R.curves[ci].depth) >= P.max_depth) continue;
    double arc = 0.0, next_release = ci == 0 && P.trunk_clear >= 0.0 ? P.trunk_clear : P.child_spacing;
    for (size_t k = 1; k + 1 < R.curves[ci].points.size() && int(R.curves.size()) < P.max_curves; ++k) {
      const auto& pts = R.curves[ci].points;
      arc += glm::length(pts[k] - pts[k - 1]);
      if (arc < next_release) continue;
      next_release += P.child_spacing;
      // Release only where the parent owns the cell (its path may run through its own
      // parent's cells): a child then only ever stands in cells of itself or its parent.
      if (R.owner[R.cell_of(pts[k])] != int32_t(ci)) continue;
      glm::dvec3 dir = pts[k + 1] - pts[k - 1];
      if (three_d) {  // [ours] leave the parent tilted off its tangent in a random azimuth
        glm::dvec3 t = glm::normalize(dir);
        glm::dvec3 h = std::abs(t.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        glm::dvec3 u = glm::normalize(glm::cross(t, h)), w = glm::cross(t, u);
        double az = rng.uniform(0.0, 6.283185307179586);
        dir = t + 0.6 * (std::cos(az) * u + std::sin(az) * w);
      }
      double sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
      glm::dvec3 at = pts[k];
      MagneticCurve child;
      int32_t id = int32_t(R.curves.size());
      for (size_t p = 0; p < P.pairs.size(); ++p) {
        if (try_curve(id, int32_t(ci), at, dir, sign, P.pairs[p], child)) {
          child.parent = int32_t(ci);
          child.parent_point = uint32_t(k);
          child.depth = R.curves[ci].depth + 1;
          child.pair = int(p);
          R.curves.push_back(std::move(child));
          break;
        }
      }
    }
  }
  return R;
}

std::string magnetic_svg(const MagneticResult& r, glm::dvec2 size) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << size.x << ' ' << size.y
    << "\" width=\"" << size.x << "\" height=\"" << size.y << "\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"#f4ecd8\"/>\n"
    << "<g fill=\"none\" stroke=\"#6b4a1a\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
  for (const MagneticCurve& c : r.curves) {
    double width = std::max(0.6, 4.0 * std::pow(0.7, double(c.depth)));
    s << "<polyline stroke-width=\"" << width << "\" points=\"";
    for (size_t i = 0; i < c.points.size(); ++i)
      s << (i ? " " : "") << c.points[i].x << ',' << (size.y - c.points[i].y);
    s << "\"/>\n";
  }
  s << "</g>\n</svg>\n";
  return s.str();
}

void write_magnetic_svg(const MagneticResult& r, glm::dvec2 size, const std::filesystem::path& out) {
  std::ofstream f(out, std::ios::binary);
  if (!f) throw InputError(out.string(), 0, "--svg", "cannot write file");
  f << magnetic_svg(r, size);
  if (!f) throw InputError(out.string(), 0, "--svg", "write failed");
}

}  // namespace forest
