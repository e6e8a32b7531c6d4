// URDF loading through urdfdom. A URDF joint is
//   T_parent_child(q) = origin * Rot(axis, q)
// and telear's canonical form needs the joint to move about z, so each movable joint becomes
//   before = (fixed joints folded in) * origin * R_align,  after = R_align^T
// with R_align turning z onto the axis; trailing fixed joints (flange, tool0) fold into the
// last joint's `after`, so frame n is the tip link.
//
// urdfdom checks the syntax (numbers, required elements, links named by joints, one root) and
// reports why through console_bridge; we capture those messages for the error. It does not
// check what this file does: a link that is the child of two joints (a cycle), zero axes,
// lower > upper, mimic joints (of missing joints, in loops, on the chain) and the tip.

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "telear/core/robot_loader.hpp"
#include "telear/core/utf8.hpp"
#include "urdf_description.hpp"

namespace telear::core {
namespace {

// Defaults for what URDF leaves out: it has no acceleration limit at all, and continuous
// joints often carry no velocity limit. Conservative values; docs/robot-files.md says so.
constexpr double kDefaultVelocity = 1.0;          // rad/s or m/s
constexpr double kAccelerationPerVelocity = 4.0;  // 1/s: full speed in 0.25 s

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return T;
}

bool finite_pose(const urdf::Pose& p) {
  double x = 0, y = 0, z = 0, w = 1;
  p.rotation.getQuaternion(x, y, z, w);
  return std::isfinite(p.position.x) && std::isfinite(p.position.y) &&
         std::isfinite(p.position.z) && std::isfinite(x) && std::isfinite(y) && std::isfinite(z) &&
         std::isfinite(w);
}

bool is_movable(const urdf::Joint& j) {
  return j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS ||
         j.type == urdf::Joint::PRISMATIC;
}

JointType joint_type(const urdf::Joint& j) {
  return j.type == urdf::Joint::PRISMATIC ? JointType::kPrismatic : JointType::kRevolute;
}

// before = origin * align, after = align^T (align turns z onto the axis).
void canonical(const urdf::Joint& j, Eigen::Isometry3d& before, Eigen::Isometry3d& after) {
  const Eigen::Vector3d axis = Eigen::Vector3d(j.axis.x, j.axis.y, j.axis.z).normalized();
  Eigen::Isometry3d align = Eigen::Isometry3d::Identity();
  align.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
  before = to_isometry(j.parent_to_joint_origin_transform) * align;
  after = align.inverse();
}

Eigen::Isometry3d z_motion(JointType type, double value) {
  Eigen::Isometry3d Z = Eigen::Isometry3d::Identity();
  if (type == JointType::kPrismatic) {
    Z.translation().z() = value;
  } else {
    Z.linear() = Eigen::AngleAxisd(value, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  return Z;
}

std::string join(const std::vector<std::string>& names, const std::string& separator = ", ") {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : separator) + n;
  return out;
}

// Collects urdfdom's error messages while it parses (console_bridge has one global handler:
// the mutex keeps two loaders from swapping it under each other).
class UrdfdomErrors : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

// The joints' parent -> child graph read from the XML before urdfdom builds it: urdfdom links
// its links by shared_ptr, and a graph with a cycle that it then refuses (a joint whose child
// is its parent, a -> b -> a without a root) is never freed (issue 25: found by the fuzzer,
// fuzz/crashes/urdf/). An error for a cycle, else nothing (urdfdom reports the rest).
std::optional<std::string> joint_graph_cycle(const std::string& text) {
  // TinyXML 1, the parser urdfdom itself reads the text with (it accepts what urdfdom does).
  TiXmlDocument doc;
  doc.Parse(text.c_str());
  if (doc.Error()) return std::nullopt;
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) return std::nullopt;
  const auto link_of = [](const TiXmlElement* joint, const char* which) {
    const TiXmlElement* e = joint->FirstChildElement(which);
    const char* name = e != nullptr ? e->Attribute("link") : nullptr;
    return std::string(name != nullptr ? name : "");
  };
  std::map<std::string, std::vector<std::string>> joints_of_child;
  std::map<std::string, std::string> parent_of;  // child link -> parent link
  for (const TiXmlElement* j = robot->FirstChildElement("joint"); j != nullptr;
       j = j->NextSiblingElement("joint")) {
    const char* name_attribute = j->Attribute("name");
    const std::string name = name_attribute != nullptr ? name_attribute : "";
    const std::string parent = link_of(j, "parent"), child = link_of(j, "child");
    if (parent.empty() || child.empty()) continue;
    if (parent == child) {
      return "joint '" + name + "' has link '" + child +
             "' as both its parent and its child; a URDF must be a tree";
    }
    joints_of_child[child].push_back(name);
    parent_of[child] = parent;
  }
  for (auto& [link, joints] : joints_of_child) {
    if (joints.size() > 1) {
      std::sort(joints.begin(), joints.end());
      return "link '" + link + "' is the child of several joints (" + join(joints) +
             "); a URDF must be a tree (is there a cycle?)";
    }
  }
  // Each link has one parent at most: going up from any link either ends or comes back.
  for (const auto& [start, first_parent] : parent_of) {
    std::string link = first_parent;
    for (std::size_t steps = 0; steps <= parent_of.size(); ++steps) {
      if (link == start) {
        return "the joints form a cycle through link '" + start + "'; a URDF must be a tree";
      }
      const auto up = parent_of.find(link);
      if (up == parent_of.end()) break;
      link = up->second;
    }
  }
  return std::nullopt;
}

// urdfdom links hold their children by shared_ptr: a URDF with a cycle (link a the child of
// two joints, a -> b -> a) gives a model whose links own each other, which would never be
// freed (issue 25: the fuzzer's first finding, fuzz/crashes/urdf/). The model is read here
// only; on leaving, the links' child lists are cleared, so that any graph is freed.
struct UrdfModelRelease {
  const urdf::ModelInterfaceSharedPtr& model;
  ~UrdfModelRelease() {
    if (!model) return;
    for (auto& [name, link] : model->links_) {
      if (!link) continue;
      link->child_links.clear();
      link->child_joints.clear();
    }
  }
};

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& text, std::string& why) {
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  UrdfdomErrors log;
  console_bridge::useOutputHandler(&log);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    log.errors.push_back(e.what());
    model.reset();
  }
  console_bridge::restorePreviousOutputHandler();
  why = join(log.errors, "; ");
  return model;
}

GeometryElement to_element(const urdf::GeometrySharedPtr& geometry, const urdf::Pose& origin) {
  GeometryElement e;
  e.T_link_geometry = to_isometry(origin);
  switch (geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*geometry);
      e.kind = GeometryElement::Kind::kBox;
      e.box_size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*geometry);
      e.kind = GeometryElement::Kind::kCylinder;
      e.radius = cylinder.radius;
      e.length = cylinder.length;
      break;
    }
    case urdf::Geometry::SPHERE:
      e.kind = GeometryElement::Kind::kSphere;
      e.radius = static_cast<const urdf::Sphere&>(*geometry).radius;
      break;
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*geometry);
      e.kind = GeometryElement::Kind::kMesh;
      e.mesh_uri = mesh.filename;
      e.scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      break;
    }
  }
  return e;
}

bool finite_element(const GeometryElement& e) {
  return e.T_link_geometry.matrix().allFinite() && e.box_size.allFinite() &&
         std::isfinite(e.radius) && std::isfinite(e.length) && e.scale.allFinite();
}

// How an off-chain joint moves: with the gripper (index into Gripper::joints) or held.
struct OffChainJoint {
  int gripper_joint = -1;
  double held_value = 0.0;  // rad or m, when gripper_joint < 0
};

}  // namespace

Result<std::string> read_urdf_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"cannot open URDF file '" + path + "'"};
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    return Error{"URDF '" + path + "': the file is empty"};
  }
  return text;
}

Result<UrdfDescription> describe_urdf(const std::string& text, const std::string& source,
                                      const std::string& tip_link,
                                      const std::optional<RobotFileGripper>& gripper_spec) {
  const std::string where = "URDF '" + source + "'";
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    return Error{where + ": the file is empty"};
  }
  // TinyXML 1 (ours above and urdfdom's) skips a multi-byte UTF-8 character by its lead byte's
  // length, so a sequence cut by the end of the text makes it read past it (a heap overflow,
  // found by fuzz/urdf_fuzz.cpp): XML is UTF-8, and text that is not is refused first.
  if (const auto bad = first_invalid_utf8(text)) {
    return Error{where + ": not UTF-8 text (an invalid byte sequence at byte " +
                 std::to_string(*bad) + ")"};
  }
  if (const auto cycle = joint_graph_cycle(text)) return Error{where + ": " + *cycle};
  std::string why;
  const urdf::ModelInterfaceSharedPtr urdf = parse_with_urdfdom(text, why);
  const UrdfModelRelease release{urdf};
  if (!urdf) {
    return Error{where + ": not a valid URDF (urdfdom could not parse it" +
                 (why.empty() ? std::string() : ": " + why) + ")"};
  }
  const urdf::LinkConstSharedPtr root = urdf->getRoot();
  if (!root) return Error{where + ": has no root link"};

  // A tree: every link the child of at most one joint, every link hanging from the root.
  std::map<std::string, std::vector<std::string>> parent_joints;
  for (const auto& [name, joint] : urdf->joints_) {
    parent_joints[joint->child_link_name].push_back(name);
  }
  for (const auto& [link, joints] : parent_joints) {
    if (joints.size() > 1) {
      return Error{where + ": link '" + link + "' is the child of several joints (" + join(joints) +
                   "); a URDF must be a tree (is there a cycle?)"};
    }
  }
  for (const auto& [name, link] : urdf->links_) {
    urdf::LinkConstSharedPtr l = link;
    for (std::size_t steps = 0; l && l != root && steps <= urdf->links_.size(); ++steps) {
      l = l->getParent();
    }
    if (l != root) {
      return Error{where + ": link '" + name + "' does not hang from the root link '" + root->name +
                   "' (its joints form a cycle)"};
    }
  }

  // Every joint: finite numbers, a usable axis, ordered limits, mimic of an existing joint.
  for (const auto& [name, j] : urdf->joints_) {
    const std::string what = where + ": joint '" + name + "'";
    if (!finite_pose(j->parent_to_joint_origin_transform)) {
      return Error{what + ": <origin> is not finite"};
    }
    if (is_movable(*j)) {
      const Eigen::Vector3d axis(j->axis.x, j->axis.y, j->axis.z);
      if (!axis.allFinite() || axis.norm() < 1e-9) {
        return Error{what + " has a zero or invalid axis"};
      }
    }
    if (j->limits) {
      const auto& l = *j->limits;
      if (!std::isfinite(l.lower) || !std::isfinite(l.upper) || !std::isfinite(l.velocity)) {
        return Error{what + ": <limit> is not finite"};
      }
      if (j->type != urdf::Joint::CONTINUOUS && l.lower > l.upper) {
        std::ostringstream s;
        s << what << ": <limit> lower " << l.lower << " > upper " << l.upper;
        return Error{s.str()};
      }
      if (l.velocity < 0.0) return Error{what + ": <limit> velocity is negative"};
    }
    if (j->mimic) {
      if (!std::isfinite(j->mimic->multiplier) || !std::isfinite(j->mimic->offset)) {
        return Error{what + ": <mimic> multiplier / offset is not finite"};
      }
      if (!urdf->getJoint(j->mimic->joint_name)) {
        return Error{what + " mimics '" + j->mimic->joint_name +
                     "', which is not a joint of the URDF"};
      }
    }
  }
  // Mimic chains end at a joint that mimics nobody; a loop never ends.
  for (const auto& [name, j] : urdf->joints_) {
    std::vector<std::string> seen{name};
    for (urdf::JointConstSharedPtr m = j; m->mimic;) {
      m = urdf->getJoint(m->mimic->joint_name);
      if (std::find(seen.begin(), seen.end(), m->name) != seen.end()) {
        seen.push_back(m->name);
        return Error{where + ": mimic loop " + join(seen, " -> ")};
      }
      seen.push_back(m->name);
    }
  }

  // The tip: named, or the single leaf.
  urdf::LinkConstSharedPtr tip;
  if (!tip_link.empty()) {
    tip = urdf->getLink(tip_link);
    if (!tip) return Error{where + ": has no link named '" + tip_link + "'"};
  } else {
    std::vector<std::string> leaves;
    for (const auto& [name, link] : urdf->links_) {
      if (link->child_links.empty()) {
        leaves.push_back(name);
        tip = link;
      }
    }
    if (leaves.size() != 1) {
      return Error{where + ": the tree has several leaf links (" + join(leaves) +
                   "); name the tip link"};
    }
  }

  // The chain root -> tip: path_links[k + 1] is the child of path_joints[k].
  std::vector<urdf::JointConstSharedPtr> path_joints;
  std::vector<urdf::LinkConstSharedPtr> path_links{tip};
  for (urdf::LinkConstSharedPtr link = tip; link != root; link = link->getParent()) {
    path_joints.push_back(link->parent_joint);
    path_links.push_back(link->getParent());
  }
  std::reverse(path_joints.begin(), path_joints.end());
  std::reverse(path_links.begin(), path_links.end());

  UrdfDescription out;
  RobotModel::Description& d = out.model;
  d.name = urdf->getName();
  d.source = source;
  out.root_link = root->name;
  out.tip_link = tip->name;
  std::set<std::string> chain_joints;
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();
  for (const urdf::JointConstSharedPtr& uj : path_joints) {
    chain_joints.insert(uj->name);
    const Eigen::Isometry3d origin = to_isometry(uj->parent_to_joint_origin_transform);
    if (uj->type == urdf::Joint::FIXED) {
      if (d.joints.empty()) {
        pending = pending * origin;
      } else {
        d.joints.back().after = d.joints.back().after * origin;
      }
      continue;
    }
    if (!is_movable(*uj)) {
      return Error{where + ": joint '" + uj->name +
                   "' is floating or planar; telear handles revolute, continuous, prismatic "
                   "and fixed joints"};
    }
    if (uj->mimic) {
      return Error{where + ": joint '" + uj->name + "' on the chain " + root->name + " -> " +
                   tip->name + " mimics '" + uj->mimic->joint_name +
                   "'; telear moves chain joints independently (a mimic joint is only "
                   "supported off the chain, e.g. in a gripper)"};
    }
    Joint joint;
    joint.name = uj->name;
    joint.type = joint_type(*uj);
    canonical(*uj, joint.before, joint.after);
    joint.before = pending * joint.before;
    pending = Eigen::Isometry3d::Identity();
    JointLimits& l = joint.limits;
    if (uj->type == urdf::Joint::CONTINUOUS || !uj->limits) {
      l.lower = -std::numeric_limits<double>::infinity();
      l.upper = std::numeric_limits<double>::infinity();
    } else {
      l.lower = uj->limits->lower;
      l.upper = uj->limits->upper;
    }
    l.max_velocity =
        (uj->limits && uj->limits->velocity > 0.0) ? uj->limits->velocity : kDefaultVelocity;
    l.max_acceleration = kAccelerationPerVelocity * l.max_velocity;
    d.joints.push_back(std::move(joint));
  }
  if (d.joints.empty()) {
    return Error{where + ": no movable joint between root '" + root->name + "' and tip '" +
                 tip->name + "'"};
  }
  d.named_configurations.push_back(
      {"zero", Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d.joints.size()))});

  // The gripper: driven joints first, then every joint whose mimic chain ends at one of them.
  std::map<std::string, OffChainJoint> off_chain;
  if (gripper_spec) {
    const RobotFileGripper& spec = *gripper_spec;
    Gripper g;
    g.max_opening_m = spec.max_opening_m;
    if (spec.closed.size() != spec.joints.size() || spec.open.size() != spec.joints.size()) {
      return Error{spec.where + "gripper: joints, closed and open must have the same length"};
    }
    for (std::size_t i = 0; i < spec.joints.size(); ++i) {
      const std::string what =
          spec.where + "gripper.joints[" + std::to_string(i) + "] '" + spec.joints[i] + "'";
      const urdf::JointConstSharedPtr j = urdf->getJoint(spec.joints[i]);
      if (!j) return Error{what + " is not a joint of URDF '" + source + "'"};
      if (!is_movable(*j)) return Error{what + " is not a revolute or prismatic joint"};
      if (chain_joints.count(j->name) != 0) {
        return Error{what + " is on the arm's chain " + root->name + " -> " + tip->name};
      }
      if (j->mimic) {
        return Error{what + " mimics '" + j->mimic->joint_name + "'; name the joint it follows"};
      }
      if (off_chain.count(j->name) != 0) return Error{what + " is named twice"};
      GripperJoint gj;
      gj.name = j->name;
      gj.type = joint_type(*j);
      canonical(*j, gj.before, gj.after);
      gj.closed = spec.closed[i];
      gj.open = spec.open[i];
      off_chain[j->name].gripper_joint = static_cast<int>(g.joints.size());
      g.joints.push_back(std::move(gj));
    }
    for (const auto& [name, j] : urdf->joints_) {
      if (!j->mimic || !is_movable(*j) || chain_joints.count(name) != 0) continue;
      // Compose the chain of mimics: value = multiplier * master + offset.
      double multiplier = 1.0, offset = 0.0;
      urdf::JointConstSharedPtr m = j;
      while (m->mimic) {
        offset = multiplier * m->mimic->offset + offset;
        multiplier = multiplier * m->mimic->multiplier;
        m = urdf->getJoint(m->mimic->joint_name);
      }
      const auto driven = off_chain.find(m->name);
      if (driven == off_chain.end() || driven->second.gripper_joint < 0) continue;
      const GripperJoint& master = g.joints[static_cast<std::size_t>(driven->second.gripper_joint)];
      GripperJoint gj;
      gj.name = name;
      gj.type = joint_type(*j);
      canonical(*j, gj.before, gj.after);
      gj.closed = master.closed;
      gj.open = master.open;
      gj.multiplier = multiplier;
      gj.offset = offset;
      gj.mimics = master.name;
      off_chain[name].gripper_joint = static_cast<int>(g.joints.size());
      g.joints.push_back(std::move(gj));
    }
    out.gripper = std::move(g);
  }
  // Every other movable off-chain joint is held at 0; a mimic of a held joint at its offset.
  for (const auto& [name, j] : urdf->joints_) {
    if (!is_movable(*j) || chain_joints.count(name) != 0 || off_chain.count(name) != 0) continue;
    double multiplier = 1.0, offset = 0.0;
    for (urdf::JointConstSharedPtr m = j; m->mimic; m = urdf->getJoint(m->mimic->joint_name)) {
      offset = multiplier * m->mimic->offset + offset;
      multiplier = multiplier * m->mimic->multiplier;
    }
    off_chain[name].held_value = offset;
  }

  // Chain links: their frame and T_frame_link (identity for the frame's own link).
  struct ChainLink {
    int frame = 0;
    Eigen::Isometry3d T_frame_link = Eigen::Isometry3d::Identity();
  };
  std::map<std::string, ChainLink> chain_links;
  {
    std::vector<int> group(path_links.size(), 0);
    for (std::size_t k = 1; k < path_links.size(); ++k) {
      group[k] = group[k - 1] + (path_joints[k - 1]->type == urdf::Joint::FIXED ? 0 : 1);
    }
    for (std::size_t k = 0; k < path_links.size(); ++k) {
      ChainLink c;
      c.frame = group[k];
      if (group[k] == 0) {
        for (std::size_t j = 0; j < k; ++j) {
          c.T_frame_link =
              c.T_frame_link * to_isometry(path_joints[j]->parent_to_joint_origin_transform);
        }
      } else {
        Eigen::Isometry3d T_link_frame = Eigen::Isometry3d::Identity();
        for (std::size_t j = k; j < path_joints.size() && group[j + 1] == group[k]; ++j) {
          T_link_frame =
              T_link_frame * to_isometry(path_joints[j]->parent_to_joint_origin_transform);
        }
        c.T_frame_link = T_link_frame.inverse();
      }
      chain_links[path_links[k]->name] = c;
    }
  }

  // Every link, depth first from the root, with its steps from its chain frame.
  std::function<Status(const urdf::LinkConstSharedPtr&, int, std::vector<AttachmentStep>)> visit =
      [&](const urdf::LinkConstSharedPtr& link, int frame,
          std::vector<AttachmentStep> steps) -> Status {
    if (const auto c = chain_links.find(link->name); c != chain_links.end()) {
      frame = c->second.frame;
      steps.clear();
      if (c->second.T_frame_link.matrix() != Eigen::Matrix4d::Identity()) {
        steps.push_back({c->second.T_frame_link, -1});
      }
    }
    RobotLink rl;
    rl.name = link->name;
    rl.frame = frame;
    rl.steps = steps;
    for (std::size_t i = 0; i < link->visual_array.size(); ++i) {
      const auto& v = link->visual_array[i];
      if (!v || !v->geometry) continue;
      GeometryElement e = to_element(v->geometry, v->origin);
      e.material_name = v->material_name;
      urdf::MaterialSharedPtr material = v->material;
      if (!material && !v->material_name.empty()) material = urdf->getMaterial(v->material_name);
      if (material) {
        e.rgba = Eigen::Vector4f(material->color.r, material->color.g, material->color.b,
                                 material->color.a);
      }
      if (!finite_element(e) || (e.rgba && !e.rgba->allFinite())) {
        return Error{where + ": link '" + link->name + "' visual " + std::to_string(i) +
                     " has a number that is not finite"};
      }
      rl.visuals.push_back(std::move(e));
    }
    for (std::size_t i = 0; i < link->collision_array.size(); ++i) {
      const auto& c = link->collision_array[i];
      if (!c || !c->geometry) continue;
      GeometryElement e = to_element(c->geometry, c->origin);
      if (!finite_element(e)) {
        return Error{where + ": link '" + link->name + "' collision " + std::to_string(i) +
                     " has a number that is not finite"};
      }
      rl.collisions.push_back(std::move(e));
    }
    out.links.push_back(std::move(rl));

    for (const urdf::JointSharedPtr& j : link->child_joints) {
      const urdf::LinkConstSharedPtr child = urdf->getLink(j->child_link_name);
      if (!child) continue;  // urdfdom refuses such files; kept for safety
      std::vector<AttachmentStep> next = steps;
      auto add_fixed = [&next](const Eigen::Isometry3d& T) {
        if (!next.empty() && next.back().gripper_joint < 0) {
          next.back().fixed = next.back().fixed * T;
        } else {
          next.push_back({T, -1});
        }
      };
      const auto moving = off_chain.find(j->name);
      if (chain_joints.count(j->name) != 0 || moving == off_chain.end()) {
        // On the chain (the child is a chain link: its steps are reset) or fixed/floating/planar.
        add_fixed(to_isometry(j->parent_to_joint_origin_transform));
      } else if (moving->second.gripper_joint >= 0) {
        next.push_back({Eigen::Isometry3d::Identity(), moving->second.gripper_joint});
      } else {
        Eigen::Isometry3d before, after;
        canonical(*j, before, after);
        add_fixed(before * z_motion(joint_type(*j), moving->second.held_value) * after);
      }
      if (Status s = visit(child, frame, std::move(next)); !s) return s;
    }
    return Status::Ok();
  };
  if (Status s = visit(root, 0, {}); !s) return s.error();
  return out;
}

Result<RobotModel> parse_urdf(const std::string& text, const std::string& source,
                              const std::string& tip_link) {
  auto described = describe_urdf(text, source, tip_link);
  if (!described) return described.error();
  return RobotModel::create(std::move(described.value().model));
}

Result<RobotModel> load_urdf_file(const std::string& path, const std::string& tip_link) {
  auto text = read_urdf_text(path);
  if (!text) return text.error();
  return parse_urdf(*text, path, tip_link);
}

}  // namespace telear::core
