#pragma once
// Internal to deepcheck::robots: the TinyXML pass over a URDF before urdfdom reads it
// (urdf_prepass.cpp).

#include <map>
#include <set>
#include <string>

namespace deepcheck::robots::detail {

/// Checks the URDF text `xml` (syntax, at most maxLinks links and joints, finiteness of every
/// number read, joints forming a tree) and returns it without what is never read (<visual>,
/// <inertial>), for urdfdom. Fills jointOrder (joint name -> position in the file) and
/// visualLinks (the links with a <visual>, which the returned text no longer shows). Throws
/// std::invalid_argument naming `context` and the element.
std::string prepareUrdf(const std::string& xml, const std::string& context, int maxLinks,
                        std::map<std::string, int>& jointOrder, std::set<std::string>& visualLinks);

}  // namespace deepcheck::robots::detail
