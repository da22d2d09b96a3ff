"""Benchmark: a linear density field on a 1M-triangle closed mesh against uniform density.

The acceptance bound of issue 5: integrating ρ = 2400 (1 + 0.1 z) over the
signed tetrahedra of a closed mesh costs at most 3× the uniform (exact
divergence-theorem) mass properties of the same mesh.

Run: ``python bench/density.py [--triangles N] [--repeat R] [--smoke]`` (``--smoke``: a
small torus, once, no target judged). Prints the
timings, the ratio, and checks both answers against the torus's closed forms
(faceted torus, so only to the faceting error).
"""

from __future__ import annotations

import argparse

from _common import time_call, torus_triangles


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--triangles", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--smoke", action="store_true", help="tiny sizes, no target judged")
    args = parser.parse_args(argv)
    if args.smoke:
        args.triangles, args.repeat = 2_000, 1

    from plumbob.bodies.density_field import DensityField
    from plumbob.bodies.graded import with_density_field
    from plumbob.bodies.solid import MeshSolid

    tris = torus_triangles(args.triangles)
    mesh = MeshSolid(tris, density=2400.0)
    field = DensityField.from_expression("2400 * (1 + 0.1*z)")
    graded = with_density_field(mesh, field)

    uniform_time = time_call(mesh.mass_properties, args.repeat)
    uniform = mesh.mass_properties()
    # A fresh body each time: GradedBody caches its integral.
    linear_time = time_call(lambda: with_density_field(mesh, field).mass_properties(), args.repeat)
    linear = graded.mass_properties()
    ratio = linear_time / uniform_time
    print(f"mesh: {len(tris):,} triangles (torus R = 1 m, r = 0.3 m)")
    print(f"uniform 2400 kg/m³:          {uniform_time * 1e3:8.1f} ms   mass {uniform.mass:.9g} kg")
    print(f"linear 2400 (1 + 0.1 z):     {linear_time * 1e3:8.1f} ms   mass {linear.mass:.9g} kg")
    print(f"ratio linear / uniform:      {ratio:8.2f}×   (acceptance: at most 3×)")
    # The field is odd in z about the torus's mid-plane: same mass, centre lifted by
    # 0.1 ∫z² dV / V = 0.1 · r²/4 (torus: ∫z² dV = V r²/4).
    print(f"mass agreement:              {abs(linear.mass - uniform.mass) / uniform.mass:.1e}")
    print(f"centre z: {linear.center_of_mass[2]:.9g} m (closed form for the smooth torus "
          f"{0.1 * 0.3**2 / 4:.9g} m)")
    return 0 if ratio <= 3 or args.smoke else 1


if __name__ == "__main__":
    raise SystemExit(main())
