// The scene schema: the deal.II far field and its interface with the blocks.
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"
#include "common/wave_type.h"
#include "fem/far_field_description.h"

namespace ddafem::schema
{
BoundKeys<fem::FarFieldDescription> far_field_keys()
{
  using S = fem::FarFieldDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("material", T::string).required().meaning("name of a material in `materials`"));
  k.add(key("lower", T::vector2)
            .unit("m")
            .default_note("required unless `mesh` is given")
            .meaning("lower-left corner [x0, y0]"));
  k.add(key("upper", T::vector2)
            .unit("m")
            .default_note("required unless `mesh` is given")
            .meaning("upper-right corner [x1, y1]"));
  k.field("element_size", &S::element_size)
      .unit("m")
      .at_least(0)
      .meaning("element edge length; 0: VS / (max_frequency points_per_wavelength) x degree");
  k.field("max_frequency", &S::max_frequency)
      .unit("Hz")
      .at_least(0)
      .meaning("highest frequency to resolve (needed when element_size is 0, unless the "
               "incident wave is a record: then its spectrum's f99)");
  k.field("points_per_wavelength", &S::points_per_wavelength)
      .greater_than(0)
      .meaning("nodes per shortest S wavelength");
  k.field("degree", &S::degree).at_least(1).meaning("FE_Q degree: 1 or 2");
  k.add(key("hole", T::section)
            .section("far_field.hole")
            .default_note("none")
            .meaning("a hole in the rectangle (for the near field), elements graded towards it"));
  k.add(key("mesh", T::section)
            .section("far_field.mesh")
            .default_note("none: the generated rectangle")
            .meaning("a Gmsh mesh instead of the rectangle"));
  k.field("solver", &S::solver)
      .meaning("direct: sparse LU factorized once; cg: conjugate gradients (Jacobi), "
               "warm-started from the predicted displacement: faster on large models");
  k.field("solver_tolerance", &S::solver_tolerance)
      .greater_than(0)
      .less_than(1)
      .meaning("cg: residual relative to the right-hand side (1e-12: monitors agree with "
               "`direct` to about 1e-8)");
  k.add(key("static_stage", T::section)
            .section("far_field.static_stage")
            .default_note("none: the dynamic stage starts unstressed")
            .meaning("gravity and in-situ stress solved statically before the dynamic stage"));
  k.add(key("rayleigh", T::section)
            .section("far_field.rayleigh")
            .default_note("none")
            .meaning("Rayleigh damping C += alpha M + beta K"));
  k.add(key("boundaries", T::section_list)
            .section("far_field.boundaries[i]")
            .default_note("all parts free")
            .meaning("what each side of the rectangle does"));
  k.add(key("incident", T::section)
            .section("far_field.incident")
            .default_note("none")
            .meaning("a vertically incident plane wave entering through an `input` side"));
  k.add(key("integrator", T::choice)
            .choices(names_of<fem::Integrator>())
            .default_note("dda with time.integrator dda, else newmark_trapezoidal")
            .meaning("the far field's Newmark scheme"));
  return k;
}

Section far_field_section()
{
  return {
      "far_field",
      "A rectangular elastic continuum meshed with FE_Q elements (deal.II), in the scene's "
      "`analysis.plane` and advanced with the trapezoidal rule (exact for energy) at `time.dt`, "
      "or with `dda` (damps like the blocks). Monitors may lie in it. With `blocks` the far "
      "field surrounds them (a `hole`, or a side they adjoin) and `interface` ties the two into "
      "one implicit system per step of the blocks (per half step of Bathe's scheme), on the dt "
      "levels time.dt / 2^k of adaptive control.",
      far_field_keys().keys()};
}

BoundKeys<coupling::InterfaceDescription> interface_keys()
{
  using S = coupling::InterfaceDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("part", &S::part).required().meaning("the far field's part the blocks fill or adjoin");
  k.field("normal_stiffness", &S::normal_stiffness)
      .unit("N/m")
      .default_note("that of `joint_material`, else of `joints.default`")
      .greater_than(0)
      .meaning("normal spring per tied edge end (a bonded joint's p): an edge's ties share 2 p "
               "by their quadrature weights");
  k.field("shear_ratio", &S::shear_ratio)
      .default_note("that of `joint_material`, else of `joints.default`, else 0.4")
      .greater_than(0)
      .meaning("shear spring / normal spring");
  k.add(key("joint_material", T::string)
            .default_note("none: ties of unlimited strength (a linear interface)")
            .meaning("a joint material whose friction angle, cohesion and tensile strength the "
                     "ties follow (Mohr-Coulomb per tie, open / slide / lock in the open-close "
                     "iteration): blocks can slip on or separate from the far field"));
  k.field("points_per_face", &S::points_per_face)
      .at_least(1)
      .meaning("Gauss points per piece of a block edge between far-field face ends (3 "
               "integrates the ties exactly against degree-2 faces)");
  k.field("tolerance", &S::tolerance)
      .unit("m")
      .at_least(0)
      .meaning("largest distance of a tied block edge from the part; 0: 1e-6 of the blocks' "
               "extent");
  return k;
}

Section interface_section()
{
  return {"interface",
          "Blocks tied to the far field (coupling/README.md). The block edges on the far field's "
          "part are tied at Gauss points (composite over the pieces between far-field face ends) "
          "by normal and shear springs, like a bonded joint; the far field is condensed onto the "
          "ties so that blocks and far field advance in one implicit system per step with "
          "`time.dt` (`time.control` must be fixed). The blocks must cover the part exactly.",
          interface_keys().keys()};
}

BoundKeys<fem::BoundaryCondition> far_field_boundary_keys()
{
  using S = fem::BoundaryCondition;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("part", T::choice)
            .required()
            .choices(names_of<fem::BoundaryPart>())
            .meaning("the side, or the hole's boundary"));
  k.field("type", &S::kind)
      .required()
      .meaning("fixed: zero displacement; lysmer: dashpots t = -rho (a VP (v.n) n + b VS (v "
               "- (v.n) n)) (Lysmer & Kuhlemeyer 1969); input: those dashpots plus the "
               "traction rho c 2 v_in of the incident wave (Joyner & Chen 1975); roller: the "
               "displacement component the incident wave does not move is fixed (uy for a "
               "vertical SV wave, ux for P), keeping a column one-dimensional; free_field "
               "(left, right): dashpots on the motion relative to a 1D column solved "
               "alongside plus its stress, t = sigma_ff n - D (v - v_ff) (free-field "
               "boundary of Zienkiewicz et al. 1989, Nielsen 2006)");
  k.field("a", &S::a).greater_than(0).meaning("normal dashpot factor");
  k.field("b", &S::b).greater_than(0).meaning("tangential dashpot factor");
  k.add(key("springs", T::section)
            .section("far_field.boundaries[i].springs")
            .default_note("none: dashpots only")
            .meaning("lysmer: springs beside the dashpots (viscous-spring boundary) for waves "
                     "radiating from a source inside"));
  return k;
}

Section far_field_boundaries_section()
{
  return {"far_field.boundaries[i]",
          "One side of the far-field rectangle. Sides not listed are traction free.",
          far_field_boundary_keys().keys()};
}

BoundKeys<fem::BoundarySprings> far_field_springs_keys()
{
  using S = fem::BoundarySprings;
  BoundKeys<S> k;
  k.field("center", &S::center)
      .unit("m")
      .required()
      .meaning("where the waves come from (the source, the opening)");
  k.field("alpha_n", &S::alpha_n)
      .at_least(0)
      .meaning("normal spring factor (Liu et al. 2006, 2D: 0.8 to 1.2)");
  k.field("alpha_t", &S::alpha_t).at_least(0).meaning("tangential spring factor (0.35 to 0.65)");
  return k;
}

Section far_field_boundaries_springs_section()
{
  return {"far_field.boundaries[i].springs",
          "The viscous-spring artificial boundary (Deeks & Randolph 1994; Liu et al. 2006): "
          "springs K = G / R (alpha_n n n^T + alpha_t (I - n n^T)) per unit length beside the "
          "dashpots, R the distance from the source. A wave from a source inside reaches the "
          "boundary as a cylindrical wave whose near-field part the dashpots alone reflect.",
          far_field_springs_keys().keys()};
}

BoundKeys<fem::HoleDescription> far_field_hole_keys()
{
  using S = fem::HoleDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("shape", T::choice)
            .required()
            .choices(names_of<fem::HoleShape>())
            .meaning("the hole's shape"));
  k.add(key("lower", T::vector2)
            .unit("m")
            .default_note("rectangle only")
            .meaning("lower-left "
                     "corner"));
  k.add(key("upper", T::vector2)
            .unit("m")
            .default_note("rectangle only")
            .meaning("upper-right "
                     "corner"));
  k.add(key("vertices", T::point_list)
            .unit("m")
            .default_note("polygon only")
            .meaning("at least 3 vertices, star-shaped about their centroid (e.g. convex)"));
  k.add(key("center", T::vector2).unit("m").default_note("circle only").meaning("centre"));
  k.add(key("radius", T::number)
            .unit("m")
            .default_note("circle only")
            .greater_than(0)
            .meaning("radius; the boundary follows the circle under refinement"));
  k.field("element_size", &S::element_size)
      .unit("m")
      .at_least(0)
      .meaning("element size at the hole; 0: the far size (no grading)");
  k.field("growth_ratio", &S::growth_ratio)
      .greater_than(1)
      .meaning("size ratio of neighbouring elements away from the hole");
  return k;
}

Section far_field_hole_section()
{
  return {
      "far_field.hole",
      "A hole in the far-field rectangle, its boundary the part `hole`. The mesh is an O-grid of "
      "quadrilaterals between the hole and a box twice its size, a Cartesian grid outside, "
      "refined near the hole (hanging nodes) until each element's longest edge is at most "
      "min(far size, element_size + (growth_ratio - 1) d), d the distance from the hole. Give "
      "the keys of the shape: rectangle `lower`, `upper`; polygon `vertices`; circle `center`, "
      "`radius`.",
      far_field_hole_keys().keys()};
}

BoundKeys<fem::StaticStage> far_field_static_stage_keys()
{
  using S = fem::StaticStage;
  BoundKeys<S> k;
  k.field("gravity", &S::gravity)
      .unit("m/s^2")
      .default_note("the scene's `gravity`")
      .meaning("body acceleration of the far field, e.g. [0, -9.81]");
  add_in_situ_keys(k, &S::stress, &S::stress_gradient);
  k.field("reference_y", &S::reference_y)
      .unit("m")
      .default_note("the top of the far field")
      .meaning("height where the in-situ stress is `stress`");
  k.field("support", &S::support)
      .meaning("how `lysmer` and `input` parts are held in the static stage: fixed, or roller "
               "(normal displacement only; the hole is held fixed)");
  return k;
}

Section far_field_static_stage_section()
{
  return {
      "far_field.static_stage",
      "A static stage ahead of the dynamic one: K u_s = f_gravity - integral(B^T sigma0) with "
      "the `lysmer` and `input` parts held (`support`), sigma0(y) = stress + stress_gradient (y "
      "- reference_y) the in-situ stress. The reactions are then kept as constant forces and "
      "the dashpots act: the dynamic stage starts from u_s at rest. Monitors and snapshots "
      "report displacements relative to u_s and the total stress sigma0 + D B u.",
      far_field_static_stage_keys().keys()};
}

Section far_field_rayleigh_section()
{
  using T = ValueType;
  return {
      "far_field.rayleigh",
      "Rayleigh damping C += alpha M + beta K; its damping ratio at circular frequency omega is "
      "alpha / (2 omega) + beta omega / 2. Give `alpha` and `beta`, or `ratio` and "
      "`frequencies` (then alpha = 2 ratio w1 w2 / (w1 + w2), beta = 2 ratio / (w1 + w2): the "
      "ratio is exact at both frequencies and lower between them).",
      {key("alpha", T::number).unit("1/s").at_least(0).default_note("0").meaning("mass factor"),
       key("beta", T::number).unit("s").at_least(0).default_note("0").meaning("stiffness factor"),
       key("ratio", T::number)
           .at_least(0)
           .less_than(1)
           .default_note("none")
           .meaning("damping ratio at both `frequencies`, e.g. 0.05"),
       key("frequencies", T::vector2)
           .unit("Hz")
           .greater_than(0)
           .default_note("none")
           .meaning("[f1, f2], f1 < f2: where the ratio is exact")}};
}

Section far_field_mesh_section()
{
  using T = ValueType;
  return {
      "far_field.mesh",
      "A quadrilateral mesh from a Gmsh file (ASCII msh 2 or 4, read by deal.II GridIn) instead "
      "of the rectangle: the far field is the file's mesh, not refined. Its physical line tags "
      "name the boundary parts; boundary lines with other tags or none are free.",
      {key("file", T::string).required().meaning("path of the .msh file, relative to the scene"),
       key("parts", T::section)
           .section("far_field.mesh.parts")
           .default_note("none: all boundary lines free")
           .meaning("physical line tag of each named part")}};
}

Section far_field_mesh_parts_section()
{
  using T = ValueType;
  return {"far_field.mesh.parts",
          "Physical line tags of the parts used in `far_field.boundaries` (each tag must occur in "
          "the file).",
          {key("bottom", T::integer).at_least(1).default_note("none").meaning("tag of `bottom`"),
           key("right", T::integer).at_least(1).default_note("none").meaning("tag of `right`"),
           key("top", T::integer).at_least(1).default_note("none").meaning("tag of `top`"),
           key("left", T::integer).at_least(1).default_note("none").meaning("tag of `left`"),
           key("hole", T::integer).at_least(1).default_note("none").meaning("tag of `hole`")}};
}

Section far_field_incident_section()
{
  using T = ValueType;
  return {"far_field.incident",
          "A plane wave travelling up from the `input` side: particle velocity v_in(t), horizontal "
          "for SV, vertical for P.",
          {key("type", T::choice).required().choices(names_of<WaveType>()).meaning("wave type"),
           key("velocity", T::time_function)
               .required()
               .meaning("v_in(t) [m/s] of the incident (upgoing) wave")}};
}

} // namespace ddafem::schema
