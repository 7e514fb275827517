/* The stress field below a Hertz contact and its maxima, in closed form (pure C99).
 *
 * Units: lengths in any one consistent unit, stresses divided by the peak pressure p0.
 * Frame: x along the semi-major axis a, y along the semi-minor axis b (a >= b > 0),
 * z >= 0 the depth into the body, tension positive.
 *
 * Every function returns 0 on success or one of the HERTZ_STRESS_E* codes below for
 * invalid input, in which case every output is NaN.
 */
#ifndef HERTZ_STRESS_KERNEL_H
#define HERTZ_STRESS_KERNEL_H

#ifdef __cplusplus
extern "C" {
#endif

#define HERTZ_STRESS_OK 0
#define HERTZ_STRESS_EAXES 1     /* a, b not finite, b <= 0 or a < b */
#define HERTZ_STRESS_ENU 2       /* nu not finite or outside (-1, 0.5] */
#define HERTZ_STRESS_EPOINT 3    /* a coordinate is not finite */
#define HERTZ_STRESS_EDEPTH 4    /* z < 0 */

/* Cauchy stress / p0 at (x, y, z), z >= 0: out = {sxx, syy, szz, syz, sxz, sxy}.
   Exact at z = 0 inside the ellipse (szz = -p/p0), on it and outside it. Coordinates
   beyond about 1e150 a overflow. */
int hertz_point_stress(double a, double b, double nu, double x, double y, double z,
                       double out[6]);

/* Maxima below a point contact (stresses / p0, positions in the unit of a and b):
   out[0], out[1]   tau_max, z:   the largest (s1 - s3)/2 on the z axis and its depth
   out[2], out[3]   von_mises, z: the largest von Mises stress on the z axis and its depth
   out[4..6]        tau_orthogonal, y, z: the largest |syz| in the plane x = 0 and where
                    (y > 0); independent of nu
   out[7..9]        tensile, x, y: the largest principal stress on the surface (in the plane
                    z = 0; it is reached on the edge of the contact) and where on the edge
                    (x, y >= 0). For nu = 0.5 it is 0 (the surface is stress free outside
                    the contact and compressed inside), reported at (a, 0).
   The maxima on the z axis are global maxima of the shear and von Mises stress below the
   contact (the axis is where they peak for every b/a and nu in (-1, 0.5]) only in the
   usual sense of Hertz theory; this function searches the axis only. */
int hertz_subsurface(double a, double b, double nu, double out[12]);

/* Line contact (plane strain), semi-width b, x across the strip, z depth:
   out = {sxx, szz, sxz, syy} / p0 with syy = nu (sxx + szz) (McEwen 1949). */
int hertz_line_stress(double b, double nu, double x, double z, double out[4]);

/* Maxima below a line contact:
   out = {tau_max, z_tau_max, von_mises, z_von_mises, tau_orthogonal (max |sxz|), x, z}.
   tau_max and von Mises are searched on the z axis (x = 0); tau_orthogonal is reached at
   x = +-b sqrt(3)/2, z = b/2 with value p0/4 (x > 0 returned). */
int hertz_line_subsurface(double b, double nu, double out[7]);

#ifdef __cplusplus
}
#endif

#endif
