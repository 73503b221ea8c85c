/* mesh_gltf.cpp — glTF 2.0 loader (.gltf / .glb) on top of Debian's tinygltf.
 * The only C++ file of the library: every entry point catches all exceptions, and
 * every accessor is bounds-checked here before a byte of it is read. */
extern "C" {
#include "mesh/mesh.h"
}

#include <tiny_gltf.h> /* declarations only: the implementation is libtinygltf.so */

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

/* Inputs above 1 GiB are refused (tinygltf also takes lengths as unsigned int). */
const size_t kMaxInputBytes = size_t(1) << 30;
/* Node hierarchy guards: depth (a cycle shows up as unbounded depth) and the
 * number of mesh instances (shared subtrees can multiply exponentially). */
const int kMaxDepth = 256;
const size_t kMaxInstances = size_t(1) << 20;

struct LoadError {
    snell_status status;
    std::string msg;
};

[[noreturn]] void fail(snell_status st, const std::string &msg) { throw LoadError{st, msg}; }

/* --- filesystem callbacks -------------------------------------------------- */
/* Memory input must not touch the filesystem: a buffer uri naming a file is an
 * error there. File input may read sibling files, but only regular ones (no
 * /dev/zero) and not beyond kMaxInputBytes. */
struct FsPolicy {
    bool allow_files;
};

bool fs_exists(const std::string &path, void *user)
{
    const FsPolicy *pol = static_cast<const FsPolicy *>(user);
    struct stat sb;
    return pol->allow_files && stat(path.c_str(), &sb) == 0 && S_ISREG(sb.st_mode);
}

std::string fs_expand(const std::string &path, void *) { return path; /* no ~ or $VAR expansion */ }

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    const FsPolicy *pol = static_cast<const FsPolicy *>(user);
    if (!pol->allow_files) {
        if (err) *err += "external file '" + path + "' referenced from in-memory glTF\n";
        return false;
    }
    struct stat sb;
    if (stat(path.c_str(), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        if (err) *err += "'" + path + "' is not a readable regular file\n";
        return false;
    }
    if (static_cast<unsigned long long>(sb.st_size) > kMaxInputBytes) {
        if (err) *err += "'" + path + "' is larger than 1 GiB\n";
        return false;
    }
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) {
        if (err) *err += "cannot open '" + path + "'\n";
        return false;
    }
    out->resize(static_cast<size_t>(sb.st_size));
    size_t got = out->empty() ? 0 : std::fread(out->data(), 1, out->size(), f);
    std::fclose(f);
    if (got != out->size()) {
        if (err) *err += "short read on '" + path + "'\n";
        return false;
    }
    return true;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err) *err += "writing is not supported\n";
    return false;
}

/* Images are irrelevant for geometry: skip decoding them (and stb_image's
 * attack surface) entirely. */
bool skip_image(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *,
                int, void *)
{
    return true;
}

/* --- accessor validation --------------------------------------------------- */
struct View {
    const unsigned char *base; /* first element */
    size_t stride, count, elem_size;
    int component_type;
};

size_t component_size(int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

bool add_ok(size_t a, size_t b, size_t *r)
{
    if (a > SIZE_MAX - b) return false;
    *r = a + b;
    return true;
}

/* Resolves accessor idx into a bounds-checked strided view. what names it in
 * errors. type is the required TINYGLTF_TYPE_*; index accessors pass
 * is_index to allow the three unsigned integer component types. */
View get_view(const tinygltf::Model &m, int idx, int type, bool is_index, const char *what)
{
    char buf[256];
    if (idx < 0 || static_cast<size_t>(idx) >= m.accessors.size()) {
        std::snprintf(buf, sizeof buf, "%s accessor %d does not exist (%zu accessors)", what, idx,
                      m.accessors.size());
        fail(SNELL_E_PARSE, buf);
    }
    const tinygltf::Accessor &a = m.accessors[static_cast<size_t>(idx)];
    if (a.sparse.isSparse) {
        std::snprintf(buf, sizeof buf, "%s accessor %d is sparse (not supported)", what, idx);
        fail(SNELL_E_UNSUPPORTED, buf);
    }
    if (a.type != type) {
        std::snprintf(buf, sizeof buf, "%s accessor %d has type %d, expected %d", what, idx, a.type, type);
        fail(SNELL_E_PARSE, buf);
    }
    if (is_index) {
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            std::snprintf(buf, sizeof buf, "%s accessor %d has component type %d, expected an unsigned integer",
                          what, idx, a.componentType);
            fail(SNELL_E_PARSE, buf);
        }
    } else if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        /* KHR_mesh_quantization (integer positions/normals) is not supported */
        std::snprintf(buf, sizeof buf, "%s accessor %d has component type %d, only FLOAT is supported", what,
                      idx, a.componentType);
        fail(SNELL_E_UNSUPPORTED, buf);
    }
    if (a.count > SNELL_MESH_MAX_VERTICES * size_t(3)) {
        std::snprintf(buf, sizeof buf, "%s accessor %d has %zu elements (limit %zu)", what, idx, a.count,
                      SNELL_MESH_MAX_VERTICES * size_t(3));
        fail(SNELL_E_LIMIT, buf);
    }
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= m.bufferViews.size()) {
        std::snprintf(buf, sizeof buf, "%s accessor %d has no valid bufferView (%d)", what, idx, a.bufferView);
        fail(SNELL_E_PARSE, buf);
    }
    const tinygltf::BufferView &bv = m.bufferViews[static_cast<size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size()) {
        std::snprintf(buf, sizeof buf, "bufferView %d references missing buffer %d", a.bufferView, bv.buffer);
        fail(SNELL_E_PARSE, buf);
    }
    const std::vector<unsigned char> &data = m.buffers[static_cast<size_t>(bv.buffer)].data;
    size_t view_end;
    if (!add_ok(bv.byteOffset, bv.byteLength, &view_end) || view_end > data.size()) {
        std::snprintf(buf, sizeof buf, "bufferView %d (offset %zu, length %zu) exceeds buffer %d of %zu bytes",
                      a.bufferView, bv.byteOffset, bv.byteLength, bv.buffer, data.size());
        fail(SNELL_E_PARSE, buf);
    }
    const size_t csize = component_size(a.componentType);
    const size_t ncomp = type == TINYGLTF_TYPE_SCALAR ? 1 : 3;
    const size_t elem = csize * ncomp;
    size_t stride = bv.byteStride ? bv.byteStride : elem;
    /* glTF: byteStride is 4..252 and a multiple of the component size; it must
     * at least cover one element or elements would overlap. */
    if (bv.byteStride && (bv.byteStride < elem || bv.byteStride > 252 || bv.byteStride % csize != 0)) {
        std::snprintf(buf, sizeof buf, "bufferView %d has invalid byteStride %zu for %s elements of %zu bytes",
                      a.bufferView, bv.byteStride, what, elem);
        fail(SNELL_E_PARSE, buf);
    }
    size_t need = 0;
    if (a.count > 0) {
        /* byteOffset + stride * (count - 1) + elem <= byteLength, overflow-checked */
        if ((a.count - 1) > (SIZE_MAX - elem) / stride || !add_ok(a.byteOffset, (a.count - 1) * stride + elem, &need) ||
            need > bv.byteLength) {
            std::snprintf(buf, sizeof buf,
                          "%s accessor %d (offset %zu, %zu x %zu bytes, stride %zu) exceeds bufferView %d of %zu bytes",
                          what, idx, a.byteOffset, a.count, elem, stride, a.bufferView, bv.byteLength);
            fail(SNELL_E_PARSE, buf);
        }
    }
    View v;
    v.base = data.data() + bv.byteOffset + a.byteOffset;
    v.stride = stride;
    v.count = a.count;
    v.elem_size = elem;
    v.component_type = a.componentType;
    return v;
}

void read_vec3(const View &v, size_t i, float out[3]) { std::memcpy(out, v.base + i * v.stride, 12); }

uint32_t read_index(const View &v, size_t i)
{
    const unsigned char *p = v.base + i * v.stride;
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t s;
        std::memcpy(&s, p, 2);
        return s;
    }
    default: {
        uint32_t u;
        std::memcpy(&u, p, 4);
        return u;
    }
    }
}

/* --- transforms (column-major 4x4, doubles) -------------------------------- */
struct Mat4 {
    double m[16];
};

Mat4 identity()
{
    Mat4 r;
    for (int i = 0; i < 16; i++) r.m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    return r;
}

Mat4 mul(const Mat4 &a, const Mat4 &b)
{
    Mat4 r;
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

void check_finite(const std::vector<double> &v, int node, const char *what)
{
    for (double d : v)
        if (!std::isfinite(d)) {
            char buf[128];
            std::snprintf(buf, sizeof buf, "node %d: %s has a non-finite value", node, what);
            fail(SNELL_E_PARSE, buf);
        }
}

/* Local transform of a node: matrix if given, else T * R * S (glTF 2.0 §5.25). */
Mat4 local_transform(const tinygltf::Node &n, int idx)
{
    char buf[128];
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16) {
            std::snprintf(buf, sizeof buf, "node %d: matrix has %zu elements, expected 16", idx, n.matrix.size());
            fail(SNELL_E_PARSE, buf);
        }
        check_finite(n.matrix, idx, "matrix");
        Mat4 r;
        for (int i = 0; i < 16; i++) r.m[i] = n.matrix[static_cast<size_t>(i)];
        return r;
    }
    if ((!n.translation.empty() && n.translation.size() != 3) || (!n.scale.empty() && n.scale.size() != 3) ||
        (!n.rotation.empty() && n.rotation.size() != 4)) {
        std::snprintf(buf, sizeof buf, "node %d: translation/rotation/scale has the wrong number of elements", idx);
        fail(SNELL_E_PARSE, buf);
    }
    check_finite(n.translation, idx, "translation");
    check_finite(n.rotation, idx, "rotation");
    check_finite(n.scale, idx, "scale");
    Mat4 t = identity(), r = identity(), s = identity();
    if (!n.translation.empty())
        for (int i = 0; i < 3; i++) t.m[12 + i] = n.translation[static_cast<size_t>(i)];
    if (!n.scale.empty())
        for (int i = 0; i < 3; i++) s.m[i * 5] = n.scale[static_cast<size_t>(i)];
    if (!n.rotation.empty()) {
        /* unit quaternion (x, y, z, w); normalised here to tolerate rounding */
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        double len = std::sqrt(x * x + y * y + z * z + w * w);
        if (!(len > 0.0)) {
            std::snprintf(buf, sizeof buf, "node %d: rotation quaternion is zero", idx);
            fail(SNELL_E_PARSE, buf);
        }
        x /= len; y /= len; z /= len; w /= len;
        r.m[0] = 1 - 2 * (y * y + z * z); r.m[4] = 2 * (x * y - z * w);     r.m[8] = 2 * (x * z + y * w);
        r.m[1] = 2 * (x * y + z * w);     r.m[5] = 1 - 2 * (x * x + z * z); r.m[9] = 2 * (y * z - x * w);
        r.m[2] = 2 * (x * z - y * w);     r.m[6] = 2 * (y * z + x * w);     r.m[10] = 1 - 2 * (x * x + y * y);
    }
    return mul(t, mul(r, s));
}

/* --- geometry accumulation -------------------------------------------------- */
struct Builder {
    const tinygltf::Model &model;
    std::vector<float> pos, nrm;
    std::vector<uint32_t> idx;
    size_t instances = 0;
    explicit Builder(const tinygltf::Model &m) : model(m) {}

    void add_primitive(const tinygltf::Primitive &p, const Mat4 &M, int mesh_idx);
    void visit(int node, const Mat4 &parent, int depth);
};

void Builder::add_primitive(const tinygltf::Primitive &p, const Mat4 &M, int mesh_idx)
{
    char buf[256];
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return; /* points and lines have no surface */
    auto pit = p.attributes.find("POSITION");
    if (pit == p.attributes.end()) return; /* nothing to draw */
    View vp = get_view(model, pit->second, TINYGLTF_TYPE_VEC3, false, "POSITION");
    auto nit = p.attributes.find("NORMAL");
    bool has_n = nit != p.attributes.end();
    View vn = has_n ? get_view(model, nit->second, TINYGLTF_TYPE_VEC3, false, "NORMAL") : View();
    if (has_n && vn.count != vp.count) {
        std::snprintf(buf, sizeof buf, "mesh %d: NORMAL has %zu elements, POSITION %zu", mesh_idx, vn.count,
                      vp.count);
        fail(SNELL_E_PARSE, buf);
    }
    /* corner list (local vertex ids) */
    if (p.indices < -1) { /* tinygltf uses -1 for "absent"; anything lower is invalid */
        std::snprintf(buf, sizeof buf, "mesh %d: indices accessor %d does not exist", mesh_idx, p.indices);
        fail(SNELL_E_PARSE, buf);
    }
    std::vector<uint32_t> corners;
    size_t ncorner = vp.count;
    View vi;
    if (p.indices >= 0) {
        vi = get_view(model, p.indices, TINYGLTF_TYPE_SCALAR, true, "indices");
        ncorner = vi.count;
    }
    corners.resize(ncorner);
    for (size_t i = 0; i < ncorner; i++) {
        uint32_t v = p.indices >= 0 ? read_index(vi, i) : static_cast<uint32_t>(i);
        if (v >= vp.count) {
            std::snprintf(buf, sizeof buf, "mesh %d: index %u at position %zu is out of range (%zu vertices)",
                          mesh_idx, v, i, vp.count);
            fail(SNELL_E_PARSE, buf);
        }
        corners[i] = v;
    }
    /* triangles (glTF 2.0 §3.7.2.1 topology rules); trailing corners that do not
     * make a whole triangle are ignored */
    std::vector<uint32_t> tris;
    if (p.mode == TINYGLTF_MODE_TRIANGLES) {
        tris.assign(corners.begin(), corners.begin() + static_cast<std::ptrdiff_t>(ncorner / 3 * 3));
    } else if (ncorner >= 3) {
        tris.reserve(3 * (ncorner - 2));
        for (size_t i = 0; i + 2 < ncorner; i++) {
            if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                /* every other triangle is flipped to keep the winding */
                tris.push_back(corners[i]);
                tris.push_back(corners[i + 1 + (i & 1)]);
                tris.push_back(corners[i + 2 - (i & 1)]);
            } else {
                tris.push_back(corners[0]);
                tris.push_back(corners[i + 1]);
                tris.push_back(corners[i + 2]);
            }
        }
    }
    if (tris.empty()) return;
    if (pos.size() / 3 + vp.count > SNELL_MESH_MAX_VERTICES || (idx.size() + tris.size()) / 3 > SNELL_MESH_MAX_TRIANGLES) {
        std::snprintf(buf, sizeof buf, "scene exceeds %u vertices or %u triangles", SNELL_MESH_MAX_VERTICES,
                      SNELL_MESH_MAX_TRIANGLES);
        fail(SNELL_E_LIMIT, buf);
    }
    /* Normals transform by the inverse transpose of the upper 3x3, which is the
     * cofactor matrix divided by the determinant; only the direction matters,
     * so the cofactor matrix times sign(det) does. */
    const double *m = M.m;
    double cof[9] = {
        m[5] * m[10] - m[6] * m[9], m[6] * m[8] - m[4] * m[10], m[4] * m[9] - m[5] * m[8],
        m[9] * m[2] - m[10] * m[1], m[10] * m[0] - m[8] * m[2], m[8] * m[1] - m[9] * m[0],
        m[1] * m[6] - m[2] * m[5],  m[2] * m[4] - m[0] * m[6],  m[0] * m[5] - m[1] * m[4]};
    /* cof[3*c + r]: column c of the cofactor matrix, i.e. cofactor of m(r, c) */
    double det = m[0] * cof[0] + m[4] * cof[3] + m[8] * cof[6];
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return; /* zero scale hides the instance */
    double sg = det > 0 ? 1.0 : -1.0;
    size_t base = pos.size() / 3;
    pos.resize(pos.size() + 3 * vp.count);
    nrm.resize(nrm.size() + 3 * vp.count);
    bool need_smooth = !has_n;
    for (size_t i = 0; i < vp.count; i++) {
        float p3[3];
        read_vec3(vp, i, p3);
        for (int r = 0; r < 3; r++) {
            double w = m[r] * p3[0] + m[4 + r] * p3[1] + m[8 + r] * p3[2] + m[12 + r];
            if (!std::isfinite(w) || std::fabs(w) > 3.0e38) {
                std::snprintf(buf, sizeof buf, "mesh %d: vertex %zu is not finite after the node transform", mesh_idx, i);
                fail(SNELL_E_PARSE, buf);
            }
            pos[3 * (base + i) + static_cast<size_t>(r)] = static_cast<float>(w);
        }
        if (has_n) {
            float n3[3];
            read_vec3(vn, i, n3);
            double o[3];
            /* inverse transpose = cof (as a matrix applied to n, rows of cof^T) */
            for (int r = 0; r < 3; r++) o[r] = sg * (cof[r] * n3[0] + cof[3 + r] * n3[1] + cof[6 + r] * n3[2]);
            double len = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            if (len > 1e-30 && std::isfinite(len)) {
                for (int r = 0; r < 3; r++) nrm[3 * (base + i) + static_cast<size_t>(r)] = static_cast<float>(o[r] / len);
            } else {
                need_smooth = true; /* zero or NaN normal in the file: recompute */
            }
        }
    }
    /* A mirroring transform (det < 0) turns counter-clockwise into clockwise;
     * glTF says the winding then flips, so swap two corners to keep CCW. */
    if (det < 0)
        for (size_t t = 0; t + 2 < tris.size(); t += 3) std::swap(tris[t + 1], tris[t + 2]);
    if (need_smooth) {
        std::vector<float> sm(3 * vp.count);
        snell__mesh_compute_normals(&pos[3 * base], tris.data(), static_cast<uint32_t>(vp.count),
                                    static_cast<uint32_t>(tris.size() / 3), sm.data());
        for (size_t i = 0; i < vp.count; i++) {
            float *d = &nrm[3 * (base + i)];
            if (!has_n || !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0.5f)) std::memcpy(d, &sm[3 * i], 12);
        }
    }
    idx.reserve(idx.size() + tris.size());
    for (uint32_t c : tris) idx.push_back(static_cast<uint32_t>(base + c));
}

void Builder::visit(int node, const Mat4 &parent, int depth)
{
    char buf[160];
    if (node < 0 || static_cast<size_t>(node) >= model.nodes.size()) {
        std::snprintf(buf, sizeof buf, "node %d does not exist (%zu nodes)", node, model.nodes.size());
        fail(SNELL_E_PARSE, buf);
    }
    if (depth > kMaxDepth) {
        std::snprintf(buf, sizeof buf, "node hierarchy deeper than %d at node %d (cycle?)", kMaxDepth, node);
        fail(SNELL_E_PARSE, buf);
    }
    if (++instances > kMaxInstances) {
        std::snprintf(buf, sizeof buf, "more than %zu node instances", kMaxInstances);
        fail(SNELL_E_LIMIT, buf);
    }
    const tinygltf::Node &n = model.nodes[static_cast<size_t>(node)];
    Mat4 world = mul(parent, local_transform(n, node));
    if (n.mesh >= 0) {
        if (static_cast<size_t>(n.mesh) >= model.meshes.size()) {
            std::snprintf(buf, sizeof buf, "node %d references missing mesh %d", node, n.mesh);
            fail(SNELL_E_PARSE, buf);
        }
        for (const tinygltf::Primitive &p : model.meshes[static_cast<size_t>(n.mesh)].primitives)
            add_primitive(p, world, n.mesh);
    }
    for (int c : n.children) visit(c, world, depth + 1);
}

/* Roots to draw: the default scene, else scene 0, else every node that is
 * nobody's child. */
std::vector<int> scene_roots(const tinygltf::Model &m)
{
    if (!m.scenes.empty()) {
        size_t s = (m.defaultScene >= 0 && static_cast<size_t>(m.defaultScene) < m.scenes.size())
                       ? static_cast<size_t>(m.defaultScene) : 0;
        return m.scenes[s].nodes;
    }
    std::vector<char> is_child(m.nodes.size(), 0);
    for (const tinygltf::Node &n : m.nodes)
        for (int c : n.children)
            if (c >= 0 && static_cast<size_t>(c) < m.nodes.size()) is_child[static_cast<size_t>(c)] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < m.nodes.size(); i++)
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    return roots;
}

/* tinygltf and nlohmann::json convert nested JSON (e.g. "extras") recursively,
 * so deeply nested input overflows the stack: a 200000-deep array segfaulted
 * in testing. Measure the nesting depth first (brackets outside strings). */
void check_json_depth(const unsigned char *s, size_t n)
{
    const size_t kMaxJsonDepth = 512; /* real glTF files stay below ~20 */
    size_t depth = 0;
    bool in_str = false;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = s[i];
        if (in_str) {
            if (c == '\\') i++;
            else if (c == '"') in_str = false;
        } else if (c == '"') {
            in_str = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) fail(SNELL_E_LIMIT, "JSON nested deeper than 512 levels");
        } else if ((c == ']' || c == '}') && depth > 0) {
            depth--;
        }
    }
}

/* GLB container header check before tinygltf sees it (12-byte header, then
 * a JSON chunk that must fit). */
void check_glb(const unsigned char *d, size_t size)
{
    char buf[160];
    uint32_t version, length, clen, ctype;
    if (size < 20) fail(SNELL_E_PARSE, "GLB: truncated header");
    std::memcpy(&version, d + 4, 4);
    std::memcpy(&length, d + 8, 4);
    std::memcpy(&clen, d + 12, 4);
    std::memcpy(&ctype, d + 16, 4);
    if (version != 2) {
        std::snprintf(buf, sizeof buf, "GLB: version %u, only 2 is supported", version);
        fail(SNELL_E_UNSUPPORTED, buf);
    }
    if (length > size || length < 20) {
        std::snprintf(buf, sizeof buf, "GLB: header says %u bytes, have %zu (truncated?)", length, size);
        fail(SNELL_E_PARSE, buf);
    }
    if (ctype != 0x4E4F534Au /* "JSON" */ || clen > length - 20) {
        std::snprintf(buf, sizeof buf, "GLB: bad JSON chunk (type 0x%08x, %u bytes)", ctype, clen);
        fail(SNELL_E_PARSE, buf);
    }
}

snell_status load(snell_ctx *ctx, const unsigned char *data, size_t size, const std::string &base_dir,
                  bool allow_files, snell_mesh **out)
{
    try {
        if (size > kMaxInputBytes) fail(SNELL_E_LIMIT, "glTF input larger than 1 GiB");
        tinygltf::TinyGLTF loader;
        tinygltf::Model model;
        FsPolicy pol = {allow_files};
        tinygltf::FsCallbacks fs = {fs_exists, fs_expand, fs_read, fs_write, &pol};
        loader.SetFsCallbacks(fs);
        loader.SetImageLoader(skip_image, nullptr);
        std::string err, warn;
        bool ok;
        bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
        if (glb) {
            check_glb(data, size);
            uint32_t jlen;
            std::memcpy(&jlen, data + 12, 4);
            check_json_depth(data + 20, jlen);
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned int>(size), base_dir);
        } else {
            check_json_depth(data, size);
            ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char *>(data),
                                            static_cast<unsigned int>(size), base_dir);
        }
        if (!ok) {
            while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
            fail(SNELL_E_PARSE, "tinygltf: " + (err.empty() ? std::string("unknown error") : err));
        }
        Builder b(model);
        Mat4 id = identity();
        for (int r : scene_roots(model)) b.visit(r, id, 0);
        if (b.idx.empty()) fail(SNELL_E_PARSE, "no triangle primitives in the scene");

        const snell_alloc *al = snell__ctx_alloc(ctx);
        size_t nv = b.pos.size() / 3, nt = b.idx.size() / 3;
        float *pos = static_cast<float *>(snell__calloc(al, 3 * nv, sizeof(float)));
        float *nrm = static_cast<float *>(snell__calloc(al, 3 * nv, sizeof(float)));
        uint32_t *idx = static_cast<uint32_t *>(snell__calloc(al, 3 * nt, sizeof(uint32_t)));
        if (!pos || !nrm || !idx) {
            snell__free(al, pos);
            snell__free(al, nrm);
            snell__free(al, idx);
            fail(SNELL_E_NOMEM, "out of memory for the mesh");
        }
        std::memcpy(pos, b.pos.data(), 3 * nv * sizeof(float));
        std::memcpy(nrm, b.nrm.data(), 3 * nv * sizeof(float));
        std::memcpy(idx, b.idx.data(), 3 * nt * sizeof(uint32_t));
        return snell__mesh_adopt(ctx, al, pos, nrm, idx, static_cast<uint32_t>(nv), static_cast<uint32_t>(nt), out);
    } catch (const LoadError &e) {
        return snell__fail(ctx, e.status, "glTF: %s", e.msg.c_str());
    } catch (const std::bad_alloc &) {
        return snell__fail(ctx, SNELL_E_NOMEM, "glTF: out of memory");
    } catch (const std::exception &e) {
        return snell__fail(ctx, SNELL_E_PARSE, "glTF: %s", e.what());
    } catch (...) {
        return snell__fail(ctx, SNELL_E_PARSE, "glTF: unexpected exception");
    }
}

} // namespace

extern "C" snell_status snell_mesh_load_gltf_mem(snell_ctx *ctx, const void *data, size_t size, snell_mesh **out)
{
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_gltf_mem: out is NULL");
    *out = NULL;
    if (!data || !size) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_gltf_mem: no data");
    return load(ctx, static_cast<const unsigned char *>(data), size, "", false, out);
}

extern "C" snell_status snell_mesh_load_gltf(snell_ctx *ctx, const char *path, snell_mesh **out)
{
    if (!out) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_gltf: out is NULL");
    *out = NULL;
    if (!path) return snell__fail(ctx, SNELL_E_INVALID_ARG, "snell_mesh_load_gltf: path is NULL");
    try {
        std::vector<unsigned char> bytes;
        std::string err;
        FsPolicy pol = {true};
        struct stat sb;
        if (stat(path, &sb) != 0) return snell__fail(ctx, SNELL_E_IO, "cannot open '%s'", path);
        if (static_cast<unsigned long long>(sb.st_size) > kMaxInputBytes)
            return snell__fail(ctx, SNELL_E_LIMIT, "'%s' is larger than 1 GiB", path);
        if (!fs_read(&bytes, &err, path, &pol)) {
            while (!err.empty() && err.back() == '\n') err.pop_back();
            return snell__fail(ctx, SNELL_E_IO, "glTF: %s", err.c_str());
        }
        if (bytes.empty()) return snell__fail(ctx, SNELL_E_PARSE, "glTF: '%s' is empty", path);
        /* external buffers are resolved relative to the file's directory */
        std::string p(path), dir;
        size_t slash = p.find_last_of('/');
        if (slash != std::string::npos) dir = p.substr(0, slash);
        snell_status st = load(ctx, bytes.data(), bytes.size(), dir, true, out);
        return st;
    } catch (...) {
        return snell__fail(ctx, SNELL_E_NOMEM, "glTF: out of memory reading '%s'", path);
    }
}
