// The files planners read spheres from: cuRobo's YAML, MoveIt's SRDF, a spherised URDF.
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <tinyxml2.h>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "io/atomic_file.h"
#include "io/input_file.h"
#include "sphys/error.h"
#include "sphys/tools/spherize.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Nine significant digits give every float back exactly.
std::string number(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
  return text;
}

std::string vector_text(const Vec3& v) {
  return number(v.x()) + " " + number(v.y()) + " " + number(v.z());
}

void emit_sphere(YAML::Emitter& out, const Sphere& s) {
  out << YAML::BeginMap << YAML::Key << "center" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int k = 0; k < 3; ++k) out << s.center[k];
  out << YAML::EndSeq << YAML::Key << "radius" << YAML::Value << s.radius << YAML::EndMap;
}

std::string curobo_text(const Robot& robot, std::span<const LinkSpheres> links) {
  YAML::Emitter out;
  out.SetFloatPrecision(9);
  out << YAML::Comment("Spheres of " + robot.name + " (" + robot.file.filename().string() +
                       ") by sphys spherize: per link, in the link's frame (m); each link's "
                       "spheres cover its whole surface");
  out << YAML::BeginMap << YAML::Key << "collision_spheres" << YAML::Value << YAML::BeginMap;
  for (const LinkSpheres& link : links) {
    out << YAML::Key << link.link << YAML::Value << YAML::BeginSeq;
    for (const Sphere& s : link.spheres) emit_sphere(out, s);
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  out << YAML::Key << "bounding_spheres" << YAML::Value << YAML::BeginMap;
  for (const LinkSpheres& link : links) {
    out << YAML::Key << link.link << YAML::Value;
    emit_sphere(out, link.bounding);
  }
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string xml_text(const tinyxml2::XMLDocument& document) {
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);
  return printer.CStr();
}

void add_sphere_element(tinyxml2::XMLElement& parent, const Sphere& s) {
  tinyxml2::XMLElement* sphere = parent.InsertNewChildElement("sphere");
  sphere->SetAttribute("center", vector_text(s.center).c_str());
  sphere->SetAttribute("radius", number(s.radius).c_str());
}

std::string srdf_text(const Robot& robot, std::span<const LinkSpheres> links) {
  tinyxml2::XMLDocument document;
  document.InsertEndChild(document.NewDeclaration());
  document.InsertEndChild(
      document.NewComment((" Spheres of " + robot.name +
                           " by sphys spherize: per link, in the link's frame (m); "
                           "each link's spheres cover its whole surface ")
                              .c_str()));
  tinyxml2::XMLElement* root = document.NewElement("robot");
  root->SetAttribute("name", robot.name.c_str());
  document.InsertEndChild(root);
  for (const LinkSpheres& link : links) {
    tinyxml2::XMLElement* approximation = root->InsertNewChildElement("link_sphere_approximation");
    approximation->SetAttribute("link", link.link.c_str());
    for (const Sphere& s : link.spheres) add_sphere_element(*approximation, s);
  }
  return xml_text(document);
}

void parse_xml(tinyxml2::XMLDocument& document, const std::string& text, const fs::path& path) {
  if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw Error::in_file(path, std::string("not valid XML: ") + document.ErrorStr());
  }
}

std::string urdf_text(const Robot& robot, std::span<const LinkSpheres> links) {
  tinyxml2::XMLDocument document;
  parse_xml(document, read_input_file(robot.file, InputKind::kRobot), robot.file);
  std::map<std::string, const LinkSpheres*> by_link;
  for (const LinkSpheres& link : links) by_link[link.link] = &link;
  tinyxml2::XMLElement* root = document.FirstChildElement("robot");
  if (!root) throw Error::in_file(robot.file, "has no <robot> element");
  for (tinyxml2::XMLElement* element = root->FirstChildElement("link"); element;
       element = element->NextSiblingElement("link")) {
    const char* name = element->Attribute("name");
    const auto found = by_link.find(name ? name : "");
    if (found == by_link.end()) continue;
    while (tinyxml2::XMLElement* old = element->FirstChildElement("collision")) {
      element->DeleteChild(old);
    }
    const std::vector<Sphere>& spheres = found->second->spheres;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      tinyxml2::XMLElement* collision = element->InsertNewChildElement("collision");
      collision->SetAttribute("name", ("sphere_" + std::to_string(i)).c_str());
      tinyxml2::XMLElement* origin = collision->InsertNewChildElement("origin");
      origin->SetAttribute("xyz", vector_text(spheres[i].center).c_str());
      origin->SetAttribute("rpy", "0 0 0");
      tinyxml2::XMLElement* sphere =
          collision->InsertNewChildElement("geometry")->InsertNewChildElement("sphere");
      sphere->SetAttribute("radius", number(spheres[i].radius).c_str());
    }
  }
  return xml_text(document);
}

// "x y z" → the vector; throws naming the file and the element when it is not three numbers.
Vec3 read_vector(const char* text, const fs::path& path, const std::string& where) {
  std::istringstream in(text ? text : "");
  Vec3 v;
  if (!(in >> v.x() >> v.y() >> v.z()) || !v.allFinite()) {
    throw Error::in_file(path, where + ": expected three finite numbers, got \"" +
                                   std::string(text ? text : "") + "\"");
  }
  return v;
}

float read_radius(const tinyxml2::XMLElement& element, const fs::path& path,
                  const std::string& where) {
  float radius = 0.0f;
  if (element.QueryFloatAttribute("radius", &radius) != tinyxml2::XML_SUCCESS ||
      !std::isfinite(radius) || radius <= 0.0f) {
    throw Error::in_file(path, where + ": the radius must be a positive number");
  }
  return radius;
}

std::vector<LinkSpheres> read_xml(const std::string& text, const fs::path& path) {
  tinyxml2::XMLDocument document;
  parse_xml(document, text, path);
  const tinyxml2::XMLElement* root = document.FirstChildElement("robot");
  if (!root) throw Error::in_file(path, "has no <robot> element");
  std::vector<LinkSpheres> links;
  // MoveIt's SRDF.
  for (const tinyxml2::XMLElement* element = root->FirstChildElement("link_sphere_approximation");
       element; element = element->NextSiblingElement("link_sphere_approximation")) {
    LinkSpheres link;
    link.link = element->Attribute("link") ? element->Attribute("link") : "";
    const std::string where = "link_sphere_approximation \"" + link.link + "\"";
    for (const tinyxml2::XMLElement* s = element->FirstChildElement("sphere"); s;
         s = s->NextSiblingElement("sphere")) {
      link.spheres.push_back(
          {read_vector(s->Attribute("center"), path, where), read_radius(*s, path, where)});
    }
    links.push_back(std::move(link));
  }
  if (!links.empty()) return links;
  // A URDF: the links whose collision elements are all spheres.
  for (const tinyxml2::XMLElement* element = root->FirstChildElement("link"); element;
       element = element->NextSiblingElement("link")) {
    LinkSpheres link;
    link.link = element->Attribute("name") ? element->Attribute("name") : "";
    const std::string where = "link \"" + link.link + "\"";
    bool all_spheres = element->FirstChildElement("collision") != nullptr;
    for (const tinyxml2::XMLElement* c = element->FirstChildElement("collision"); c;
         c = c->NextSiblingElement("collision")) {
      const tinyxml2::XMLElement* geometry = c->FirstChildElement("geometry");
      const tinyxml2::XMLElement* sphere =
          geometry ? geometry->FirstChildElement("sphere") : nullptr;
      if (!sphere) {
        all_spheres = false;
        break;
      }
      const tinyxml2::XMLElement* origin = c->FirstChildElement("origin");
      const Vec3 centre = origin && origin->Attribute("xyz")
                              ? read_vector(origin->Attribute("xyz"), path, where)
                              : Vec3::Zero();
      link.spheres.push_back({centre, read_radius(*sphere, path, where)});
    }
    if (all_spheres) links.push_back(std::move(link));
  }
  if (links.empty()) {
    throw Error::in_file(path, "has no link_sphere_approximation and no link made of spheres");
  }
  return links;
}

Sphere yaml_sphere(const YAML::Node& node, const fs::path& path, const std::string& where) {
  try {
    const YAML::Node centre = node["center"];
    if (!centre || !centre.IsSequence() || centre.size() != 3) {
      throw Error::in_file(path, where + ": \"center\" must be a list of three numbers");
    }
    Sphere s{Vec3(centre[0].as<float>(), centre[1].as<float>(), centre[2].as<float>()),
             node["radius"].as<float>()};
    if (!s.center.allFinite() || !std::isfinite(s.radius) || s.radius <= 0.0f) {
      throw Error::in_file(path, where + ": a centre must be finite and a radius positive");
    }
    return s;
  } catch (const YAML::Exception& error) {
    throw Error::in_file(path, where + ": " + error.msg);
  }
}

std::vector<LinkSpheres> read_yaml(const std::string& text, const fs::path& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw Error::at_line(path, static_cast<std::size_t>(error.mark.line + 1), error.msg);
  }
  const YAML::Node spheres = root.IsMap() ? root["collision_spheres"] : YAML::Node();
  if (!spheres || !spheres.IsMap()) {
    throw Error::in_file(path, "has no \"collision_spheres\" map of links");
  }
  const YAML::Node bounding = root["bounding_spheres"];
  std::vector<LinkSpheres> links;
  for (const auto& entry : spheres) {
    LinkSpheres link;
    link.link = entry.first.as<std::string>();
    const std::string where = "collision_spheres/" + link.link;
    if (!entry.second.IsSequence()) throw Error::in_file(path, where + ": expected a list");
    for (std::size_t i = 0; i < entry.second.size(); ++i) {
      link.spheres.push_back(yaml_sphere(entry.second[i], path, where + "/" + std::to_string(i)));
    }
    if (bounding && bounding.IsMap() && bounding[link.link]) {
      link.bounding = yaml_sphere(bounding[link.link], path, "bounding_spheres/" + link.link);
    }
    links.push_back(std::move(link));
  }
  return links;
}

}  // namespace

SphereFileFormat parse_sphere_file_format(std::string_view name) {
  if (name == "curobo") return SphereFileFormat::Curobo;
  if (name == "srdf") return SphereFileFormat::Srdf;
  if (name == "urdf") return SphereFileFormat::Urdf;
  throw Error("unknown format \"" + std::string(name) + "\" (expected curobo, srdf or urdf)");
}

std::string_view format_name(SphereFileFormat format) {
  switch (format) {
    case SphereFileFormat::Curobo:
      return "curobo";
    case SphereFileFormat::Srdf:
      return "srdf";
    case SphereFileFormat::Urdf:
      return "urdf";
  }
  return "?";
}

void write_robot_spheres(const fs::path& path, SphereFileFormat format, const Robot& robot,
                         std::span<const LinkSpheres> links) {
  std::string text;
  switch (format) {
    case SphereFileFormat::Curobo:
      text = curobo_text(robot, links);
      break;
    case SphereFileFormat::Srdf:
      text = srdf_text(robot, links);
      break;
    case SphereFileFormat::Urdf:
      text = urdf_text(robot, links);
      break;
  }
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::vector<LinkSpheres> read_robot_spheres(const fs::path& path) {
  const std::string text = read_input_file(path, InputKind::kRobot);
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '<') return read_xml(text, path);
  return read_yaml(text, path);
}

}  // namespace sphys::tools
