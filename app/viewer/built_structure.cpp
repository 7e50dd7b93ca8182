#include "built_structure.h"

namespace viz {

accel::Result<BuiltPtr> build_structure_now(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                                            accel::BuildControl* control) {
  auto choice = accel::parse_structure(request.name, request.params);
  if (!choice) return choice.error();
  const accel::StructureInfo* info = choice.value().info;
  const accel::ParamSet& params = choice.value().params;
  auto built = std::make_shared<BuiltStructure>();
  built->scene = std::move(scene);
  built->request = request;
  built->params_text = params.to_string_all();
  auto structure = accel::build_structure(*info, *built->scene, params, request.kernel, control);
  if (!structure) return structure.error();
  // Listing a big structure's nodes takes a while too: no point once superseded.
  if (accel::build_cancelled(control)) return accel::cancelled_error();
  built->structure = std::move(structure.value());
  built->stats = built->structure->build_stats();
  built->geometry = structure_geometry(*built->structure, request.geometry);
  if (params.has("traversal")) built->traversal = params.get_choice("traversal");
  built->info = info;
  built->kind = traversal_kind(info->traversal, built->traversal);
  if (built->kind == TraversalKind::Grid && built->scene->planar()) built->kind = TraversalKind::Grid2d;
  return BuiltPtr(std::move(built));
}

}  // namespace viz
