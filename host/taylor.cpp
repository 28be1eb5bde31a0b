#include "host/taylor.h"

namespace shadesim {

Quadratic Quadratic::recentred(double x0, double y0) const {
  // u = u' + du, v = v' + dv; collect powers of u', v'.
  const double du = x0 - xc, dv = y0 - yc;
  Quadratic r;
  r.xc = x0;
  r.yc = y0;
  r.t[0] = t[0] + t[1] * dv + t[2] * du + t[3] * dv * dv + t[4] * du * dv + t[5] * du * du;
  r.t[1] = t[1] + 2.0 * t[3] * dv + t[4] * du;
  r.t[2] = t[2] + t[4] * dv + 2.0 * t[5] * du;
  r.t[3] = t[3];
  r.t[4] = t[4];
  r.t[5] = t[5];
  return r;
}

Quadratic quadratic_from_jet(const Jet2& f, double xc, double yc) {
  Quadratic q;
  q.xc = xc;
  q.yc = yc;
  q.t[0] = f.v;
  q.t[1] = f.dy;
  q.t[2] = f.dx;
  q.t[3] = 0.5 * f.dyy;
  q.t[4] = f.dxy;
  q.t[5] = 0.5 * f.dxx;
  return q;
}

Quadratic taylor_diffuse(const AffineField& N, Vec3 L, double xc, double yc) {
  const JetVec3 n = jet_of(N, xc, yc);
  return quadratic_from_jet(dot(n, L) / sqrt(dot(n, n)), xc, yc);
}

Quadratic taylor_specular_infinite(const AffineField& N, Vec3 H, double xc, double yc) {
  return taylor_diffuse(N, H, xc, yc);
}

Quadratic taylor_specular_finite(const AffineField& N, const AffineField& E, Vec3 L, double xc,
                                 double yc) {
  const JetVec3 n = jet_of(N, xc, yc);
  const JetVec3 h = jet_of(E, xc, yc) + L;
  return quadratic_from_jet(dot(n, h) / sqrt(dot(n, n) * dot(h, h)), xc, yc);
}

Quadratic taylor_phong_infinite(const AffineField& N, Vec3 L, Vec3 V, double xc, double yc) {
  const JetVec3 n = jet_of(N, xc, yc);
  const Jet2 r_dot_v = 2.0 * (dot(n, L) * dot(n, V)) / dot(n, n) + (-dot(L, V));
  return quadratic_from_jet(r_dot_v, xc, yc);
}

Quadratic taylor_phong_finite(const AffineField& N, const AffineField& E, Vec3 L, double xc,
                              double yc) {
  const JetVec3 n = jet_of(N, xc, yc);
  const JetVec3 e = jet_of(E, xc, yc);
  const Jet2 inv_e_len = reciprocal(sqrt(dot(e, e)));
  const Jet2 r_dot_v = (2.0 * (dot(n, L) * dot(n, e)) / dot(n, n) - dot(e, L)) * inv_e_len;
  return quadratic_from_jet(r_dot_v, xc, yc);
}

}  // namespace shadesim
