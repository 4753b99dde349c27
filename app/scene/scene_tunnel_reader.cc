// The `tunnel` section: read, planned (app/scene/tunnel_scene.h) and expanded into the sections of
// a scene, which is then read like any other.
#include "app/scene/scene_readers.h"
#include "app/scene/tunnel_bolts.h"
#include "app/scene/tunnel_scene.h"
#include "app/schema/bound_sections.h"

namespace ddafem::scene_reading
{
namespace
{
/// The damping ratio of tunnel scenes without `tunnel.damping.ratio` [-]: 2 % of critical, the
/// lower end of the 2-5 % usual for rock (joint slip, the main dissipation, is modelled
/// explicitly) and the amount Hatzor et al. (2004) found to fit Masada's 2000 years
/// (docs/damping.md).
constexpr double default_tunnel_damping_ratio = 0.02;

/// The `tunnel` section's joint sets and explicit joints. Their joint material names (passed on
/// to `rock_mass` with them) are checked here, so that errors name the tunnel's keys.
void read_tunnel_joints(const MapReader& r, const YAML::Node& root, dda::RockMassDescription& d)
{
  std::vector<std::string> joint_names;
  for (const auto& named : nested(root, {"joint_materials"}))
    joint_names.push_back(named.first.Scalar());
  for (const MapReader& j : r.section_list("joint_sets"))
  {
    d.joint_sets.push_back(read_joint_set(j));
    read_joint_material(j, joint_names);
  }
  for (const MapReader& j : r.section_list("joints"))
  {
    d.joints.push_back({j.vector2("from"), j.vector2("to")});
    read_joint_material(j, joint_names);
  }
}

/// The rock's material (`tunnel.rock` in `materials`), the default joint's stiffness, gravity and
/// the plane mode, from the rest of the scene.
void read_tunnel_rock(const MapReader& r, const YAML::Node& root, const Context& context,
                      TunnelDescription& t)
{
  t.rock = r.string("rock");
  const YAML::Node rock_node = nested(root, {"materials", t.rock});
  if (!rock_node.IsDefined())
    throw r.error("rock", "expected the name of a material in `materials`");
  const MapReader rock(rock_node, context.schema.section("materials.<name>"), "materials." + t.rock,
                       context);
  t.density = rock.number("density");
  t.youngs_modulus = rock.number("youngs_modulus");
  t.poisson_ratio = rock.number("poisson_ratio");
  const YAML::Node default_joint = nested(root, {"joints", "default"});
  if (default_joint.IsDefined() && default_joint.IsScalar())
  {
    const YAML::Node j = nested(root, {"joint_materials", default_joint.Scalar()});
    if (j.IsDefined())
      t.joint_normal_stiffness = MapReader(j, context.schema.section("joint_materials.<name>"),
                                           "joint_materials." + default_joint.Scalar(), context)
                                     .number("normal_stiffness");
  }
  const YAML::Node gravity = child(root, "gravity");
  if (gravity.IsDefined())
  {
    const MapReader top(root, context.schema.section(SceneSchema::top_level), "", context);
    const Vector2 g = top.vector2("gravity");
    if (!(g.y() < 0.0) || g.x() != 0.0)
      throw top.error("gravity", "expected gravity [0, -g] (downwards) with a tunnel");
    t.gravity = -g.y();
  }
  const YAML::Node plane = nested(root, {"analysis", "plane"});
  if (plane.IsDefined() && plane.IsScalar() &&
      value_of<PlaneMode>(plane.Scalar()) != PlaneMode::strain)
    throw context.locator.error(plane, "analysis.plane", plane.Scalar(),
                                "expected strain (or nothing) with a tunnel: a section through "
                                "a long tunnel is in plane strain");
}

/// `tunnel.wave`: the incident wave's type, velocity record and frequencies [Hz]. Returns the
/// velocity.
TimeFunction read_tunnel_wave(const MapReader& r, TunnelDescription& t)
{
  const MapReader wave = r.section_reader("wave");
  schema::tunnel_wave_keys().fill(wave, t); // the type
  const TimeFunction velocity = read_time_function(wave, "velocity", TimeFunctionUse::velocity);
  if (wave.has("frequency"))
    t.wave_frequency = wave.number("frequency");
  else if (velocity.dominant_frequency() > 0.0)
    t.wave_frequency = velocity.dominant_frequency();
  else
    throw wave.error("frequency", "expected the wave's dominant frequency [Hz] for a table");
  // A record's spectrum says how high its content goes; a pulse's harmonics, twice its frequency.
  if (wave.has("max_frequency"))
    t.max_frequency = wave.number("max_frequency");
  else if (velocity.record_info() != nullptr)
    t.max_frequency = std::max(velocity.characteristic_frequency(), t.wave_frequency);
  else
    t.max_frequency = 2.0 * t.wave_frequency;
  t.wave_duration = velocity.active_until();
  return velocity;
}

/// A `within` record (the motion at depth, the surface's reflection in it) under a model that
/// reaches the ground surface, which would add the reflection again: refused.
void require_no_within_record_under_surface(const MapReader& r, const TimeFunction& velocity,
                                            const TunnelPlan& plan)
{
  const RecordInfo* record = velocity.record_info();
  if (record != nullptr && record->motion == RecordMotion::within && plan.top_is_surface)
    throw r.section_reader("wave").error(
        "velocity", "a record taken `within` (at depth) already holds the ground surface's "
                    "reflection, and this model reaches the ground surface (ddafem check says "
                    "why), which would add it again: expected motion outcrop (the incident wave "
                    "is half of it) or incident");
}

/// The near field (the truncation, margins, mesh, window and time step: tunnel_keys).
void read_tunnel_domain(const MapReader& r, TunnelDescription& t)
{
  const MapReader near = r.section_reader("near_field");
  schema::tunnel_near_field_keys().fill(near, t); // size_factor
  if (near.has("lower") != near.has("upper"))
    throw near.error(near.has("lower") ? "upper" : "lower",
                     "expected both `lower` and `upper`, or neither (size_factor)");
  if (near.has("lower"))
  {
    const Vector2 lower = near.vector2("lower"), upper = near.vector2("upper");
    if (!(upper.x() > lower.x() && upper.y() > lower.y()))
      throw near.error("upper", "expected upper > lower in both x and y");
    t.near_field = std::array<Point, 2>{lower, upper};
  }
}

/// `tunnel.static` and `tunnel.settle`: the stages before and after the wave.
void read_tunnel_stages(const MapReader& r, TunnelDescription& t)
{
  schema::tunnel_static_keys().fill(r.section_reader("static"), t);
  schema::tunnel_settle_keys().fill(r.section_reader("settle"), t);
}

/// `tunnel.damping` (default: 2 % at the wave's dominant frequency, docs/damping.md; none with
/// the vb1 truncation) onto every material and joint material of the expanded scene that has no
/// `damping` of its own; the far field takes its material's as Rayleigh's beta
/// (complete_damping). Ratio 0: undamped.
void write_tunnel_damping(const MapReader& r, const TunnelDescription& t, TunnelPlan& plan,
                          YAML::Node& root)
{
  // VB I's coefficients (Bao et al. 2012, eq. 39) hold for an undamped boundary block under
  // DDA's scheme; with the rock's dashpots on its blocks the horseshoe (k0 1, no cohesion,
  // 0.1 m/s) keeps a period-2 oscillation at its base and never settles (docs/damping.md).
  const bool vb1 = t.truncation == TunnelTruncation::vb1;
  double ratio = vb1 ? 0.0 : default_tunnel_damping_ratio, frequency = t.wave_frequency;
  if (r.has("damping"))
  {
    const MapReader d = r.section_reader("damping");
    if (d.has("ratio"))
      ratio = d.number("ratio");
    if (d.has("frequency"))
      frequency = d.number("frequency");
  }
  plan.reasons.push_back(
      ratio == 0.0 ? std::string("damping of the rock: none") +
                         (vb1 ? " (truncation vb1: VB I is derived for undamped boundary blocks; "
                                "tunnel.damping.ratio sets it, docs/damping.md)"
                              : "")
                   : "damping of the rock: " + format_significant(100.0 * ratio) +
                         " % of "
                         "critical at " +
                         format_significant(frequency) +
                         " Hz, stiffness-proportional, on every material and joint material and "
                         "the far field (tunnel.damping, docs/damping.md)");
  if (ratio == 0.0)
    return;
  YAML::Node damping;
  damping["ratio"] = ratio;
  damping["frequency"] = frequency;
  for (const char* section : {"materials", "joint_materials"})
  {
    const YAML::Node& given = root;
    if (!given[section])
      continue;
    YAML::Node named = YAML::Clone(given[section]);
    for (auto entry : named)
      if (entry.second.IsMap() && !entry.second["damping"])
        entry.second["damping"] = YAML::Clone(damping);
    root[section] = named;
  }
}
} // namespace

/// The `tunnel` section: reads it, plans the model (app/scene/tunnel_scene.h) and writes the
/// sections it generates into `root`, which is then read like any scene.
TunnelPlan expand_tunnel(YAML::Node& root, const Context& context)
{
  const YAML::Node tunnel_node = child(root, "tunnel");
  const MapReader r(tunnel_node, context.schema.section("tunnel"), "tunnel", context);
  TunnelDescription t;
  read_tunnel_rock(r, root, context, t);
  read_tunnel_joints(r, root, t.rock_mass);
  // depth, k0, the truncation, margins, mesh, time step, and the rock mass's seed and chord
  // tolerance (the opening's polygon below)
  schema::tunnel_keys().fill(r, t);
  t.limits = context.limits;
  const double far = 1e12;
  t.rock_mass.openings.push_back(
      read_opening(r.section_reader("opening"),
                   {Point(-far, -far), Point(far, -far), Point(far, far), Point(-far, far)},
                   t.rock_mass.chord_tolerance));
  const TimeFunction velocity = read_tunnel_wave(r, t);
  read_tunnel_domain(r, t);
  read_tunnel_stages(r, t);
  if (r.has("bolts"))
    write_tunnel_bolts(r.section_reader("bolts"), t.rock_mass.openings[0],
                       t.rock_mass.chord_tolerance, root);

  try
  {
    TunnelPlan plan = plan_tunnel(t);
    require_no_within_record_under_surface(r, velocity, plan);
    write_tunnel_sections(t, plan,
                          {child(tunnel_node, "opening"), child(tunnel_node, "joint_sets"),
                           child(tunnel_node, "joints"), nested(tunnel_node, {"wave", "velocity"}),
                           child(tunnel_node, "lining")},
                          root);
    write_tunnel_damping(r, t, plan, root);
    return plan;
  }
  catch (const InputError& e)
  {
    throw context.locator.error(tunnel_node, "tunnel", "", e.what());
  }
}

} // namespace ddafem::scene_reading
