// 64-bit hashes of raw data and of a mesh's contents, for memos that recognise a mesh measured before
// (the search's measures and unions). Equal contents hash alike on any thread and in any run.
#pragma once

#include "acd/mesh/mesh.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace acd {

// Raw words mixed into h one by one (splitmix64's finaliser).
inline std::uint64_t mix(std::uint64_t h, const void* data, size_t bytes)
{
	const unsigned char* p = static_cast<const unsigned char*>(data);
	for (size_t i = 0; i < bytes; i += 8) {
		std::uint64_t w = 0;
		std::memcpy(&w, p + i, std::min<size_t>(8, bytes - i));
		h ^= w + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
		h ^= h >> 30, h *= 0xbf58476d1ce4e5b9ULL, h ^= h >> 27, h *= 0x94d049bb133111ebULL, h ^= h >> 31;
	}
	return h;
}

// The vertices and faces, in order.
inline std::uint64_t content_hash(const TriMesh& m)
{
	const std::uint64_t sizes[2] = {m.V.size(), m.F.size()};
	return mix(mix(mix(0, sizes, sizeof sizes), m.V.data(), m.V.size() * sizeof(Vec3)), m.F.data(), m.F.size() * sizeof(Tri));
}

} // namespace acd
