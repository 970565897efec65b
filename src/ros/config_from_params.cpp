#include "ply_slam/ros/config_from_params.h"

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

namespace ply_slam {
namespace {

YAML::Node toYaml(XmlRpc::XmlRpcValue& value) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return YAML::Node(static_cast<bool>(value));
    case XmlRpc::XmlRpcValue::TypeInt:
      return YAML::Node(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble:
      return YAML::Node(static_cast<double>(value));
    case XmlRpc::XmlRpcValue::TypeString:
      return YAML::Node(static_cast<std::string>(value));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node list(YAML::NodeType::Sequence);
      for (int i = 0; i < value.size(); ++i) list.push_back(toYaml(value[i]));
      return list;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (auto& [key, child] : value) map[key] = toYaml(child);
      return map;
    }
    default:
      return YAML::Node(YAML::NodeType::Null);
  }
}

}  // namespace

SystemConfig configFromParams(const ros::NodeHandle& nh, const std::string& key) {
  const std::string name = nh.resolveName(key);
  XmlRpc::XmlRpcValue tree;
  if (!nh.getParam(key, tree))
    throw ConfigError("config " + name +
                      ": no such parameter (load a config/*.yaml there with <rosparam>)");
  return loadConfigFromString(YAML::Dump(toYaml(tree)), "parameter " + name);
}

}  // namespace ply_slam
