#include "ply_slam/ros/tracking_back_end.h"

#include "ply_slam/dynamic/dynamic_rejector.h"
#include "ply_slam/semantic/yolo_v8_seg.h"

namespace ply_slam {

TrackingBackEnd TrackingBackEnd::fromOptions(const TrackingNodeOptions& options) {
  TrackingBackEnd back_end;
  if (!options.config.segmentation.model_path.empty())
    back_end.segmenter =
        std::make_unique<LiveSegmenter>(std::make_unique<YoloV8Seg>(options.config.segmentation),
                                        options.config.segmentation.live_threads);
  const bool segmented = back_end.segmenter != nullptr;
  back_end.make_system = [options, segmented](const PinholeCamera& camera, bool load_map) {
    SystemConfig config = options.config;
    useCamera(config, camera);
    if (!segmented) config.dynamic.mode = modeWithoutSegmenter(config.dynamic.mode);
    const MappingMode mode = options.mapping_apart    ? MappingMode::kApart
                             : options.mapping_thread ? MappingMode::kOwnThread
                                                      : MappingMode::kInline;
    auto system = std::make_unique<System>(config, mode);
    if (load_map && !options.map.empty()) system->loadMap(options.map, options.localisation_only);
    return system;
  };
  return back_end;
}

}  // namespace ply_slam
