// Marching cubes over a VoxelBlockVolume, block by block: first every block's vertices (one on
// each grid edge it owns - the +x, +y, +z edges of its voxels - where the distance changes sign
// between two observed voxels), then every cube's triangles, looking a vertex up in the block
// that owns its edge. Blocks are independent in both passes: two threads, each block's part
// written by one and joined in block order, so the mesh does not depend on the split.
// The case tables are Open3D's (Lorensen & Cline's), from the dependency's installed header.
#include <lodestone/dense/VoxelBlockVolume.h>

#include <open3d/pipelines/integration/MarchingCubesConst.h>

#include <algorithm>
#include <thread>

namespace lodestone::dense {

class BlockMesher {
  public:
    explicit BlockMesher(const VoxelBlockVolume& volume) : vol_(volume) {}

    Mesh run() {
        const std::size_t n = vol_.blocks_.size();
        parts_.assign(n, {});
        neighbours_.assign(n, {});
        forEachBlock([&](std::size_t b) { findNeighbours(b); });
        forEachBlock([&](std::size_t b) { vertices(b); });
        offsets_.assign(n + 1, 0);
        for (std::size_t b = 0; b < n; ++b) offsets_[b + 1] = offsets_[b] + parts_[b].edges.size();
        forEachBlock([&](std::size_t b) { triangles(b); });
        Mesh mesh;
        mesh.vertices.reserve(offsets_[n]);
        mesh.colours.reserve(offsets_[n]);
        for (auto& part : parts_) {
            mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
            mesh.colours.insert(mesh.colours.end(), part.colours.begin(), part.colours.end());
            mesh.triangles.insert(mesh.triangles.end(), part.triangles.begin(), part.triangles.end());
        }
        return mesh;
    }

  private:
    using Voxel = VoxelBlockVolume::Voxel;
    static constexpr int S = VoxelBlockVolume::kSide;
    static constexpr std::uint32_t kNone = ~0U;

    struct Part {
        std::vector<std::uint16_t> edges;  ///< owned edges with a vertex: voxel * 3 + axis, sorted
        std::vector<Eigen::Vector3f> vertices;
        std::vector<std::array<std::uint8_t, 3>> colours;
        std::vector<Eigen::Vector3i> triangles;
    };

    template <class F>
    void forEachBlock(F f) const {
        const std::size_t n = vol_.blocks_.size(), half = n / 2;
        std::thread other([&] {
            for (std::size_t b = half; b < n; ++b) f(b);
        });
        for (std::size_t b = 0; b < half; ++b) f(b);
        other.join();
    }

    /** The block and its neighbours at +0/+1 along each axis (index dx + 2 dy + 4 dz). */
    void findNeighbours(std::size_t b) {
        for (int k = 0; k < 8; ++k) {
            const Eigen::Vector3i c = vol_.coords_[b] + Eigen::Vector3i(k & 1, (k >> 1) & 1, (k >> 2) & 1);
            const auto it = vol_.index_.find(VoxelBlockVolume::keyOf(c));
            neighbours_[b][k] = it == vol_.index_.end() ? kNone : it->second;
        }
    }

    /** The voxel at local coordinates in [0, 2S) of block b's neighbourhood, with its block. */
    const Voxel* at(std::size_t b, int x, int y, int z, std::uint32_t* owner = nullptr) const {
        const int k = (x >= S) + 2 * (y >= S) + 4 * (z >= S);
        const std::uint32_t nb = neighbours_[b][k];
        if (owner) *owner = nb;
        if (nb == kNone) return nullptr;
        return &(*vol_.blocks_[nb])[(x % S) + S * ((y % S) + S * (z % S))];
    }

    Eigen::Vector3f position(std::size_t b, int x, int y, int z) const {
        const Eigen::Vector3i g = vol_.coords_[b] * S + Eigen::Vector3i(x, y, z);
        return (g.cast<double>() * vol_.settings_.voxelSize).cast<float>();
    }

    void vertices(std::size_t b) {
        Part& part = parts_[b];
        const auto& block = *vol_.blocks_[b];
        for (int z = 0, n = 0; z < S; ++z)
            for (int y = 0; y < S; ++y)
                for (int x = 0; x < S; ++x, ++n) {
                    const Voxel& a = block[n];
                    if (a.weight == 0) continue;
                    for (int axis = 0; axis < 3; ++axis) {
                        const Voxel* c = at(b, x + (axis == 0), y + (axis == 1), z + (axis == 2));
                        if (!c || c->weight == 0 || (a.tsdf < 0) == (c->tsdf < 0)) continue;
                        const float s = float(a.tsdf) / float(int(a.tsdf) - int(c->tsdf));
                        Eigen::Vector3f p = position(b, x, y, z);
                        p[axis] += s * float(vol_.settings_.voxelSize);
                        std::array<std::uint8_t, 3> rgb;
                        for (int k = 0; k < 3; ++k)
                            rgb[k] = static_cast<std::uint8_t>(a.rgb[k] + s * (int(c->rgb[k]) - int(a.rgb[k])) + 0.5f);
                        part.edges.push_back(static_cast<std::uint16_t>(3 * n + axis));
                        part.vertices.push_back(p);
                        part.colours.push_back(rgb);
                    }
                }
    }

    void triangles(std::size_t b) {
        Part& part = parts_[b];
        for (int z = 0; z < S; ++z)
            for (int y = 0; y < S; ++y)
                for (int x = 0; x < S; ++x) {
                    int cube = 0;
                    bool seen = true;
                    for (int i = 0; i < 8 && seen; ++i) {
                        const Voxel* c = at(b, x + shift[i].x(), y + shift[i].y(), z + shift[i].z());
                        seen = c && c->weight > 0;
                        if (seen && c->tsdf < 0) cube |= 1 << i;
                    }
                    if (!seen || edge_table[cube] == 0) continue;
                    std::uint32_t vertex[12];
                    for (int e = 0; e < 12; ++e)
                        vertex[e] = (edge_table[cube] & (1 << e)) ? vertexOn(b, x, y, z, e) : kNone;
                    for (int i = 0; tri_table[cube][i] != -1; i += 3) {
                        const std::uint32_t a = vertex[tri_table[cube][i]], c = vertex[tri_table[cube][i + 1]],
                                            d = vertex[tri_table[cube][i + 2]];
                        if (a == kNone || c == kNone || d == kNone) continue;
                        part.triangles.emplace_back(a, d, c);
                    }
                }
    }

    /** The vertex on cube edge e of the cube at (x, y, z): looked up in its owner block. */
    std::uint32_t vertexOn(std::size_t b, int x, int y, int z, int e) const {
        const Eigen::Vector4i& s = edge_shift[e];
        const int ox = x + s.x(), oy = y + s.y(), oz = z + s.z();
        std::uint32_t owner;
        if (!at(b, ox, oy, oz, &owner)) return kNone;
        const auto key = static_cast<std::uint16_t>(3 * ((ox % S) + S * ((oy % S) + S * (oz % S))) + s.w());
        const auto& edges = parts_[owner].edges;
        const auto it = std::lower_bound(edges.begin(), edges.end(), key);
        if (it == edges.end() || *it != key) return kNone;
        return static_cast<std::uint32_t>(offsets_[owner] + (it - edges.begin()));
    }

    const VoxelBlockVolume& vol_;
    std::vector<Part> parts_;
    std::vector<std::array<std::uint32_t, 8>> neighbours_;
    std::vector<std::size_t> offsets_;
};

Mesh VoxelBlockVolume::extractMesh() const { return BlockMesher(*this).run(); }

}  // namespace lodestone::dense
