// Minimal OBJ reading and writing for the command-line tools (groups by "o"/"g" lines).
#pragma once

#include "acd/mesh/mesh.h"

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace acd::bench {

// Every object of the file ("o"/"g" start a new one, unless !split); OBJ indices are global,
// each returned object has its own.
inline std::vector<TriMesh> read_obj_objects(const std::string& path, bool split = true)
{
	std::ifstream in(path);
	if (!in) throw std::runtime_error("cannot read " + path);
	std::vector<Vec3>                all;
	std::vector<std::vector<Tri>>    faces(1);
	std::string                      line;
	while (std::getline(in, line)) {
		if (line.size() < 2) continue;
		if (split && (line[0] == 'o' || line[0] == 'g') && line[1] == ' ') {
			if (!faces.back().empty()) faces.emplace_back();
			continue;
		}
		const char* s = line.c_str();
		if (s[0] == 'v' && s[1] == ' ') {
			char*  e;
			double x = std::strtod(s + 2, &e), y = std::strtod(e, &e), z = std::strtod(e, &e);
			all.emplace_back(x, y, z);
		}
		else if (s[0] == 'f' && s[1] == ' ') {
			std::vector<int>   idx;
			std::istringstream ss(line.substr(2));
			std::string        tok;
			while (ss >> tok) {
				int i = std::stoi(tok.substr(0, tok.find('/')));
				idx.push_back(i < 0 ? (int) all.size() + i : i - 1);
			}
			for (size_t k = 1; k + 1 < idx.size(); ++k) faces.back().push_back({idx[0], idx[k], idx[k + 1]});
		}
	}
	std::vector<TriMesh> out;
	for (auto& F : faces) {
		if (F.empty()) continue;
		TriMesh          m;
		std::vector<int> local(all.size(), -1);
		for (Tri& t : F)
			for (int& i : t) {
				if (i < 0 || i >= (int) all.size()) throw std::runtime_error("bad face index in " + path);
				if (local[i] < 0) {
					local[i] = (int) m.V.size();
					m.V.push_back(all[i]);
				}
				i = local[i];
			}
		m.F = std::move(F);
		out.push_back(std::move(m));
	}
	return out;
}

inline TriMesh read_obj(const std::string& path)
{
	auto objects = read_obj_objects(path, false);
	if (objects.empty()) throw std::runtime_error("no faces in " + path);
	return std::move(objects[0]);
}

inline void write_obj_objects(const std::string& path, const std::vector<TriMesh>& objects)
{
	std::ofstream out(path);
	out.precision(17);
	int base = 1;
	for (size_t i = 0; i < objects.size(); ++i) {
		out << "o hull_" << i << "\n";
		for (const Vec3& v : objects[i].V) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
		for (const Tri& t : objects[i].F) out << "f " << t[0] + base << " " << t[1] + base << " " << t[2] + base << "\n";
		base += (int) objects[i].V.size();
	}
}

} // namespace acd::bench
