// Two floats: texture coordinates (u, v).
#pragma once

namespace kappa {

struct Vec2f {
  float u = 0, v = 0;
};

inline Vec2f operator+(const Vec2f& a, const Vec2f& b) { return {a.u + b.u, a.v + b.v}; }
inline Vec2f operator-(const Vec2f& a, const Vec2f& b) { return {a.u - b.u, a.v - b.v}; }
inline Vec2f operator*(const Vec2f& a, float s) { return {a.u * s, a.v * s}; }
inline bool operator==(const Vec2f& a, const Vec2f& b) { return a.u == b.u && a.v == b.v; }

}  // namespace kappa
