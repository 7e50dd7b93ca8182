#include "built_structure.h"

#include "student/kit_structure.h"

namespace viz {

std::unique_ptr<accel::Structure> create_requested(const accel::StructureInfo& info, const accel::Scene& scene,
                                                   const accel::ParamSet& params, const StructureRequest& request) {
  std::unique_ptr<accel::Structure> s = accel::create_structure(info, scene, params, request.kernel);
  if (auto* kit = dynamic_cast<accel::KitStructure*>(s.get())) kit->set_build_call_limit(request.build_call_limit);
  return s;
}

bool stopped_at_call_limit(const accel::Structure& structure) {
  const auto* kit = dynamic_cast<const accel::KitStructure*>(&structure);
  return kit && kit->build_stopped();
}

accel::Result<BuiltPtr> build_structure_now(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                                            accel::BuildControl* control) {
  auto choice = accel::parse_structure(request.name, request.params);
  if (!choice) return choice.error();
  const accel::StructureInfo* info = choice.value().info;
  const accel::ParamSet& params = choice.value().params;
  auto built = std::make_shared<BuiltStructure>();
  built->scene = std::move(scene);
  built->request = request;
  accel::ParamSet in_use = params;
  in_use.set_planar(built->scene->planar());  // as Structure::build uses them
  built->params_text = in_use.to_string_all();
  std::unique_ptr<accel::Structure> structure = create_requested(*info, *built->scene, params, request);
  if (auto st = structure->build(*built->scene, params, control); !st) return st.error();
  // Listing a big structure's nodes takes a while too: no point once superseded.
  if (accel::build_cancelled(control)) return accel::cancelled_error();
  built->structure = std::move(structure);
  built->stats = built->structure->build_stats();
  built->request.geometry.planar = built->scene->planar();  // a 2D scene's spheres are circles
  built->geometry = structure_geometry(*built->structure, built->request.geometry);
  if (params.has("traversal")) built->traversal = params.get_choice("traversal");
  built->info = info;
  built->kind = traversal_kind(info->traversal, built->traversal);
  if (built->kind == TraversalKind::Grid && built->scene->planar()) built->kind = TraversalKind::Grid2d;
  return BuiltPtr(std::move(built));
}

}  // namespace viz
