/* The stress field below a Hertz contact and its maxima, in closed form (pure C99).
 *
 * Units: lengths in any one consistent unit, stresses divided by the peak pressure p0.
 * Frame: x along the semi-major axis a, y along the semi-minor axis b (a >= b > 0),
 * z >= 0 the depth into the body, tension positive.
 *
 * Every function returns 0 on success or one of the HERTZ_STRESS_E* codes below for
 * invalid input, in which case every output is NaN. The functions keep no state and are
 * safe to call from several threads.
 */
#ifndef HERTZ_STRESS_KERNEL_H
#define HERTZ_STRESS_KERNEL_H

#ifdef __cplusplus
extern "C" {
#endif

#define HERTZ_STRESS_OK 0
#define HERTZ_STRESS_EAXES 1     /* a, b not finite, b <= 0, a < b or b/a < 1e-70 (underflow) */
#define HERTZ_STRESS_ENU 2       /* nu not finite or outside (-1, 0.5] */
#define HERTZ_STRESS_EPOINT 3    /* a coordinate is not finite */
#define HERTZ_STRESS_EDEPTH 4    /* z < 0 */

/* Cauchy stress / p0 at (x, y, z), z >= 0: out = {sxx, syy, szz, syz, sxz, sxy}.
   Exact also on the surface z = 0, inside the contact (szz = -p/p0), on its edge and
   outside it, and on the axes; a = b and b << a need no special handling. Beyond 1e60 a
   from the centre the field is Boussinesq's for the total force (exact there), to the end of
   the double range (values below 2.2e-308 are subnormal: exact to their granularity). */
int hertz_point_stress(double a, double b, double nu, double x, double y, double z,
                       double out[6]);

/* Maxima below a point contact (stresses / p0, positions in the unit of a and b):
   out[0], out[1]  tau_max, z: the largest (s1 - s3)/2 on the z axis and its depth
                   (0 when the largest value is at the surface, as for nu <= 0 and
                   elongated contacts)
   out[2], out[3]  von_mises, z: the largest von Mises stress on the z axis and its depth
   out[4..6]       tau_orthogonal, y, z: the largest |syz| in the plane x = 0 and where
                   (y > 0); independent of nu (Lundberg & Palmgren)
   out[7..9]       tensile, x, y: the largest principal stress on the surface z = 0, inside
                   and outside the contact. It is the radial stress sxx at the end of the
                   major axis, (x, y) = (a, 0): along the edge the largest in-plane principal
                   stress decreases monotonically from (a, 0) to (0, b) for every b/a < 1
                   (checked numerically for b/a from 1e-6 to 1 - 1e-5), and for a circle it
                   is the same everywhere on the edge ((1 - 2nu)/3). It scales with
                   (1 - 2nu) and is 0 for nu = 0.5.
   out[10], out[11] reserved, set to NaN.
   The maxima on the axis are searched over all depths, including the surface; they are
   where the shear and von Mises stresses peak below a frictionless Hertz contact, but
   this function does not search off the axis. */
int hertz_subsurface(double a, double b, double nu, double out[12]);

/* Line contact (plane strain), semi-width b, x across the strip, z depth:
   out = {sxx, szz, sxz, syy} / p0 with syy = nu (sxx + szz) (McEwen 1949); Flamant's line
   force beyond 1e60 b, to the end of the double range. */
int hertz_line_stress(double b, double nu, double x, double z, double out[4]);

/* Maxima below a line contact:
   out = {tau_max, z_tau_max, von_mises, z_von_mises, tau_orthogonal (max |sxz|), x, z}.
   tau_max and von Mises are the largest on the z axis (x = 0) over all depths, in closed
   form; tau_orthogonal is p0/4 at x = +-b sqrt(3)/2, z = b/2 (x > 0 returned). */
int hertz_line_subsurface(double b, double nu, double out[7]);

#ifdef __cplusplus
}
#endif

#endif
