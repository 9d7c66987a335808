// Mesh readers and writers: round trips, every format's malformed input
// (errors name the file, line and column), assimp formats and the real
// hulls in ../shared/data.
#include "geometry/mesh_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "base/error.h"
#include "base/file_io.h"
#include "support/test_meshes.h"

namespace hull {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;
using ::testing::HasSubstr;

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("hull_mesh_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& data) const {
    std::ofstream(Path(name), std::ios::binary) << data;
    return Path(name);
  }
  static std::string Read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  // The InputError LoadMesh throws for `path`.
  static InputError LoadError(const std::string& path) {
    try {
      LoadMesh(path);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "LoadMesh(" << path << ") did not throw an InputError";
    return InputError({}, "");
  }

  fs::path dir_;
};

// A mesh with awkward coordinates (no short decimal form) and a scalar.
TriangleMesh NoisySphere() {
  TriangleMesh m = test::MakeIcosphere(3.0, 2, Vector3d(100.1, -20.2, 5.3));
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 1e-3);
  std::vector<double> dev;
  for (auto& v : m.vertices) {
    v += Vector3d(n(rng), n(rng), n(rng));
    dev.push_back(n(rng));
  }
  m.SetScalar("deviation", dev);
  m.ComputeNormals();
  return m;
}

std::string Gzip(const std::string& data) {
  z_stream zs{};
  deflateInit2(&zs, Z_BEST_SPEED, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&zs, data.size()), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

std::string Base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

template <typename T>
void AppendRaw(std::string& s, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

// A minimal glTF 2.0 file: the unit tetrahedron, buffer embedded as base64.
std::string TetrahedronGltf() {
  std::string buf;
  for (std::uint16_t i : {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}) AppendRaw(buf, i);
  for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f}) AppendRaw(buf, x);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0}]}],
 "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
         Base64(buf) + R"("}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 24, "target": 34963},
                 {"buffer": 0, "byteOffset": 24, "byteLength": 48, "target": 34962}],
 "accessors": [
  {"bufferView": 0, "componentType": 5123, "count": 12, "type": "SCALAR", "min": [0], "max": [3]},
  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]}]}
)";
}

// ---- round trips --------------------------------------------------------------

TEST_F(MeshIoTest, PlyBinaryDoubleRoundTripIsBitIdentical) {
  const TriangleMesh m = NoisySphere();
  SaveMesh(m, Path("s.ply"));
  const TriangleMesh r = LoadMesh(Path("s.ply"));
  EXPECT_EQ(r.vertices, m.vertices);
  EXPECT_EQ(r.faces, m.faces);
  ASSERT_NE(r.FindScalar("deviation"), nullptr);
  EXPECT_EQ(*r.FindScalar("deviation"), *m.FindScalar("deviation"));
}

TEST_F(MeshIoTest, PlyAsciiRoundTripIsBitIdentical) {
  const TriangleMesh m = NoisySphere();
  MeshSaveOptions o;
  o.binary = false;
  SaveMesh(m, Path("s.ply"), o);
  EXPECT_THAT(Read(Path("s.ply")), HasSubstr("format ascii 1.0\n"));
  const TriangleMesh r = LoadMesh(Path("s.ply"));
  EXPECT_EQ(r.vertices, m.vertices);
  EXPECT_EQ(r.faces, m.faces);
  EXPECT_EQ(*r.FindScalar("deviation"), *m.FindScalar("deviation"));
}

TEST_F(MeshIoTest, PlyFloatRoundsCoordinatesToFloat) {
  const TriangleMesh m = NoisySphere();
  MeshSaveOptions o;
  o.double_precision = false;
  o.include_scalars = false;
  SaveMesh(m, Path("f.ply"), o);
  const TriangleMesh r = LoadMesh(Path("f.ply"));
  ASSERT_EQ(r.vertices.size(), m.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(r.vertices[i][c], static_cast<double>(static_cast<float>(m.vertices[i][c])));
  }
  EXPECT_TRUE(r.vertex_scalars.empty());
  EXPECT_EQ(fs::file_size(Path("f.ply")),
            Read(Path("f.ply")).find("end_header\n") + 11 + m.vertices.size() * 12 + m.faces.size() * 13);
}

TEST_F(MeshIoTest, PlyHeaderIsTheStandardOne) {
  // The header CloudCompare and ParaView expect.
  TriangleMesh m = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  m.SetScalar("deviation", std::vector<double>(8, 0.5));
  SaveMesh(m, Path("b.ply"));
  const std::string text = Read(Path("b.ply"));
  EXPECT_EQ(text.substr(0, text.find("end_header\n") + 11),
            "ply\nformat binary_little_endian 1.0\ncomment written by HullInspect\nelement vertex 8\n"
            "property double x\nproperty double y\nproperty double z\nproperty double deviation\n"
            "element face 12\nproperty list uchar int vertex_indices\nend_header\n");
}

TEST_F(MeshIoTest, ObjRoundTripIsBitIdentical) {
  const TriangleMesh m = NoisySphere();
  SaveMesh(m, Path("s.obj"));
  const TriangleMesh r = LoadMesh(Path("s.obj"));
  EXPECT_EQ(r.vertices, m.vertices);
  EXPECT_EQ(r.faces, m.faces);
}

TEST_F(MeshIoTest, StlRoundTripWeldsBackToTheSameVertices) {
  const TriangleMesh m = NoisySphere();
  SaveMesh(m, Path("s.stl"));
  EXPECT_EQ(fs::file_size(Path("s.stl")), 84 + 50 * m.faces.size());
  EXPECT_NE(Read(Path("s.stl")).substr(0, 5), "solid");
  const TriangleMesh r = LoadMesh(Path("s.stl"));
  ASSERT_EQ(r.vertices.size(), m.vertices.size());
  ASSERT_EQ(r.faces.size(), m.faces.size());
  std::set<std::array<float, 3>> a, b;
  for (const auto& v : m.vertices)
    a.insert({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  for (const auto& v : r.vertices)
    b.insert({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
  EXPECT_EQ(a, b);
  EXPECT_NEAR(r.SignedVolume(), m.SignedVolume(), 1e-4);
  MeshLoadOptions raw;
  raw.weld = false;
  EXPECT_EQ(LoadMesh(Path("s.stl"), raw).vertices.size(), 3 * m.faces.size());
}

TEST_F(MeshIoTest, GzipCompressedFilesReadAndWrite) {
  const TriangleMesh m = NoisySphere();
  SaveMesh(m, Path("s.stl.gz"));
  SaveMesh(m, Path("s.ply.gz"));
  const std::string gz = Read(Path("s.stl.gz"));
  ASSERT_GE(gz.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(gz[0]), 0x1f);
  EXPECT_EQ(LoadMesh(Path("s.stl.gz")).faces.size(), m.faces.size());
  EXPECT_EQ(LoadMesh(Path("s.ply.gz")).vertices, m.vertices);
}

// ---- STL ----------------------------------------------------------------------

TEST_F(MeshIoTest, BinaryStlThatBeginsWithSolid) {
  SaveMesh(test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 2, 3)), Path("b.stl"));
  std::string data = Read(Path("b.stl"));
  std::memcpy(data.data(), "solid exported by a CAD tool", 28);
  const TriangleMesh r = LoadMesh(Write("solid.stl", data));
  EXPECT_EQ(r.faces.size(), 12u);
  EXPECT_EQ(r.vertices.size(), 8u);
  EXPECT_NEAR(r.SignedVolume(), 6.0, 1e-12);
}

TEST_F(MeshIoTest, TruncatedBinaryStl) {
  SaveMesh(test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 2, 3)), Path("b.stl"));
  std::string data = Read(Path("b.stl"));
  data.resize(data.size() - 10);
  const std::string path = Write("cut.stl", data);
  const InputError e = LoadError(path);
  EXPECT_EQ(e.where().file, path);
  EXPECT_THAT(e.what(), HasSubstr("truncated binary STL"));
  EXPECT_THAT(e.what(), HasSubstr("12 triangles"));
  EXPECT_THAT(LoadError(Write("tiny.stl", "abc")).what(), HasSubstr("truncated binary STL"));
}

TEST_F(MeshIoTest, AsciiStl) {
  const std::string text =
      "solid square\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
      "    endloop\n  endfacet\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 1 0\n      vertex 0 1 0.5e-0\n"
      "    endloop\n  endfacet\n"
      "endsolid square\n";
  MeshLoadOptions o;
  o.orient_outward = false;
  const TriangleMesh r = LoadMesh(Write("a.stl", text), o);
  EXPECT_EQ(r.faces.size(), 2u);
  EXPECT_EQ(r.vertices.size(), 4u);  // the shared diagonal welded
  // Saved with a UTF-8 byte order mark: still ASCII (it was read as binary).
  const TriangleMesh bom = LoadMesh(Write("bom.stl", "\xEF\xBB\xBF" + text), o);
  EXPECT_EQ(bom.faces.size(), 2u);
  EXPECT_EQ(bom.vertices, r.vertices);
  const std::string bad =
      "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertx 1 0 0\n   vertex 1 1 0\n"
      "  endloop\n endfacet\nendsolid x\n";
  const InputError e = LoadError(Write("bad.stl", bad));
  EXPECT_EQ(e.where().line, 5);
  EXPECT_EQ(e.where().column, 4);
  EXPECT_THAT(e.detail(), HasSubstr("expected 'vertex'"));
  const InputError n = LoadError(Write("num.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n"));
  EXPECT_EQ(n.where().line, 4);
  EXPECT_EQ(n.where().column, 12);
  EXPECT_THAT(n.detail(), HasSubstr("z coordinate"));
}

// ---- OBJ ----------------------------------------------------------------------

TEST_F(MeshIoTest, ObjIndexFormsNegativeIndicesAndPolygons) {
  const std::string text =
      "# a unit square and a triangle\nmtllib none.mtl\no thing\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n"
      "vt 0 0\nvn 0 0 1\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
      "v 2 0 0\n"
      "f -4//1 -1//1 -3//1  # a comment\n"
      "s off\nusemtl none\n";
  MeshLoadOptions o;
  o.orient_outward = false;
  const TriangleMesh r = LoadMesh(Write("p.obj", text), o);
  ASSERT_EQ(r.vertices.size(), 5u);
  ASSERT_EQ(r.faces.size(), 3u);
  EXPECT_EQ(r.faces[0], (Face{0, 1, 2}));
  EXPECT_EQ(r.faces[1], (Face{0, 2, 3}));
  EXPECT_EQ(r.faces[2], (Face{1, 4, 2}));
}

TEST_F(MeshIoTest, ObjBadIndexNamesLineAndColumn) {
  const InputError e = LoadError(Write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"));
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.where().column, 7);
  EXPECT_THAT(e.detail(), HasSubstr("face vertex index 4 out of range; expected 1 to 3"));
  EXPECT_THAT(e.what(), HasSubstr("bad.obj:4:7"));
  EXPECT_EQ(LoadError(Write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")).where().column, 3);
  EXPECT_EQ(LoadError(Write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n")).where().column, 7);
  const InputError t = LoadError(Write("text.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/1\n"));
  EXPECT_EQ(t.where().column, 7);
  EXPECT_THAT(t.detail(), HasSubstr("expected a vertex index"));
  const InputError two = LoadError(Write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"));
  EXPECT_EQ(two.where().line, 3);
  EXPECT_THAT(two.detail(), HasSubstr("at least 3"));
  const InputError coord = LoadError(Write("coord.obj", "v 0 0\n"));
  EXPECT_EQ(coord.where().line, 1);
  EXPECT_THAT(coord.detail(), HasSubstr("z coordinate"));
}

// ---- PLY ----------------------------------------------------------------------

TEST_F(MeshIoTest, PlyUnknownTypeNamesLineAndColumn) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float16 x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const InputError e = LoadError(Write("t.ply", text));
  EXPECT_EQ(e.where().line, 4);
  EXPECT_EQ(e.where().column, 10);
  EXPECT_THAT(e.detail(), HasSubstr("unknown PLY type 'float16'"));
}

TEST_F(MeshIoTest, PlyAsciiErrorsNameTheLine) {
  const std::string head =
      "ply\nformat ascii 1.0\ncomment test\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  const InputError range = LoadError(Write("r.ply", head + "3 0 1 3\n"));
  EXPECT_EQ(range.where().line, 14);
  EXPECT_EQ(range.where().column, 7);
  EXPECT_THAT(range.detail(), HasSubstr("face vertex index 3 out of range; expected 0 to 2"));
  const InputError end = LoadError(Write("e.ply", head + "3 0 1\n"));
  EXPECT_THAT(end.detail(), HasSubstr("the file ends in element 'face' 0"));
  const InputError junk = LoadError(Write("j.ply", head + "3 0 1 2\n7\n"));
  EXPECT_EQ(junk.where().line, 15);
  EXPECT_THAT(LoadError(Write("n.ply", "plx\n")).detail(), HasSubstr("expected 'ply'"));
  EXPECT_THAT(LoadError(Write("h.ply", "ply\nformat ascii 1.0\nelement vertex 0\n")).detail(),
              HasSubstr("no 'end_header'"));
  const InputError huge = LoadError(Write("huge.ply",
                                          "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                                          "property float x\nend_header\n"));
  EXPECT_EQ(huge.where().line, 3);
  EXPECT_THAT(huge.detail(), HasSubstr("announces 4000000000 'vertex' records"));
  const InputError fmt = LoadError(Write("f.ply", "ply\nformat binary 1.0\nend_header\n"));
  EXPECT_EQ(fmt.where().line, 2);
  EXPECT_THAT(fmt.detail(), HasSubstr("unknown PLY format 'binary'"));
}

TEST_F(MeshIoTest, PlyBinaryBigEndianAnyTypesPolygonsAndScalars) {
  std::string data =
      "ply\r\nformat binary_big_endian 1.0\r\nelement vertex 4\r\nproperty double x\r\nproperty int y\r\n"
      "property float z\r\nproperty uchar quality\r\nproperty list uchar short ignored\r\nproperty short temp\r\n"
      "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
      "element face 1\r\nproperty uchar flags\r\nproperty list ushort uint vertex_index\r\nend_header\r\n";
  const double xs[4] = {0.1, 1.25, 1.5, -0.75};
  const int ys[4] = {0, 0, 1, 1};
  for (int i = 0; i < 4; ++i) {
    AppendRaw(data, xs[i], true);
    AppendRaw(data, static_cast<std::int32_t>(ys[i]), true);
    AppendRaw(data, 0.5f, true);
    AppendRaw(data, static_cast<std::uint8_t>(200 + i), true);
    AppendRaw(data, static_cast<std::uint8_t>(2), true);
    AppendRaw(data, static_cast<std::int16_t>(-1), true);
    AppendRaw(data, static_cast<std::int16_t>(-2), true);
    AppendRaw(data, static_cast<std::int16_t>(-300 + i), true);
  }
  AppendRaw(data, static_cast<std::int32_t>(0), true);
  AppendRaw(data, static_cast<std::int32_t>(1), true);
  AppendRaw(data, static_cast<std::uint8_t>(7), true);
  AppendRaw(data, static_cast<std::uint16_t>(4), true);
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) AppendRaw(data, i, true);
  MeshLoadOptions o;
  o.orient_outward = false;
  const TriangleMesh r = LoadMesh(Write("be.ply", data), o);
  ASSERT_EQ(r.vertices.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(r.vertices[i], Vector3d(xs[i], ys[i], 0.5));
  EXPECT_EQ(r.faces, (std::vector<Face>{{0, 1, 2}, {0, 2, 3}}));
  ASSERT_NE(r.FindScalar("quality"), nullptr);
  EXPECT_EQ(*r.FindScalar("quality"), (std::vector<double>{200, 201, 202, 203}));
  EXPECT_EQ(*r.FindScalar("temp"), (std::vector<double>{-300, -299, -298, -297}));

  // Truncated: the face list stops short.
  const InputError e = LoadError(Write("cut.ply", data.substr(0, data.size() - 3)));
  EXPECT_THAT(e.detail(), HasSubstr("truncated binary PLY"));
  EXPECT_EQ(e.where().field, "element 'face' 0");
}

TEST_F(MeshIoTest, FacelessPlyIsAPointCloud) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float scalar_intensity\nend_header\n0 0 0 1\n1 0 0 2\n0 1 0 3\n";
  const std::string path = Write("cloud.ply", text);
  EXPECT_THAT(LoadError(path).detail(), HasSubstr("LoadPointCloud"));
  const auto pts = LoadPointCloud(path);
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_EQ(pts[2], Vector3d(0, 1, 0));
}

// ---- OFF ----------------------------------------------------------------------

TEST_F(MeshIoTest, OffWithCommentsAndAQuad) {
  const std::string text =
      "OFF\n# a square pyramid\n5 5 0\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1  # apex\n"
      "4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4 255 0 0\n3 3 0 4\n";
  OrientationReport report;
  MeshLoadOptions o;
  o.orientation = &report;
  const TriangleMesh r = LoadMesh(Write("p.off", text), o);
  EXPECT_EQ(r.vertices.size(), 5u);
  EXPECT_EQ(r.faces.size(), 6u);
  EXPECT_TRUE(report.closed);
  EXPECT_EQ(report.faces_flipped, 0);
  EXPECT_NEAR(r.SignedVolume(), 1.0 / 3.0, 1e-15);
  const InputError e = LoadError(Write("short.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n"));
  EXPECT_EQ(e.where().line, 5);
  EXPECT_THAT(e.detail(), HasSubstr("ends after 2 of 4 vertices"));
  const InputError idx = LoadError(Write("idx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"));
  EXPECT_EQ(idx.where().line, 6);
  EXPECT_EQ(idx.where().column, 7);
  EXPECT_THAT(LoadError(Write("m.off", "0FF\n")).detail(), HasSubstr("expected 'OFF'"));
  EXPECT_THAT(LoadError(Write("big.off", "OFF\n900000000 1 0\n")).detail(), HasSubstr("more vertices and faces"));
}

// ---- assimp formats -----------------------------------------------------------------

TEST_F(MeshIoTest, GltfThroughAssimp) {
  OrientationReport report;
  MeshLoadOptions o;
  o.orientation = &report;
  const TriangleMesh r = LoadMesh(Write("tet.gltf", TetrahedronGltf()), o);
  EXPECT_EQ(r.vertices.size(), 4u);
  EXPECT_EQ(r.faces.size(), 4u);
  EXPECT_TRUE(report.closed);
  EXPECT_NEAR(r.SignedVolume(), 1.0 / 6.0, 1e-7);
  // And compressed, read from memory with the extension as the hint.
  const TriangleMesh z = LoadMesh(Write("tet.gltf.gz", Gzip(TetrahedronGltf())));
  EXPECT_EQ(z.faces.size(), 4u);
  EXPECT_NEAR(z.SignedVolume(), 1.0 / 6.0, 1e-7);
  EXPECT_THAT(LoadError(Write("broken.gltf", "{\"asset\": ")).detail(),
              HasSubstr("not in the format its extension names"));
}

// ---- options, files, extensions -------------------------------------------------------

TEST_F(MeshIoTest, LoadOptionsTransformAndOrient) {
  TriangleMesh inside_out = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 2, 3));
  for (auto& f : inside_out.faces) std::swap(f[1], f[2]);
  SaveMesh(inside_out, Path("io.ply"));
  OrientationReport report;
  MeshLoadOptions o;
  o.scale = 2.0;
  o.pose = Pose::FromXyzRpy(10, 0, 0, 0, 0, M_PI / 2);
  o.orientation = &report;
  const TriangleMesh r = LoadMesh(Path("io.ply"), o);
  EXPECT_TRUE(report.was_inside_out);
  EXPECT_EQ(report.faces_flipped, 12);
  EXPECT_NEAR(r.SignedVolume(), 48.0, 1e-9);
  EXPECT_TRUE(r.Bounds().min().isApprox(Vector3d(6, 0, 0), 1e-12));
  EXPECT_TRUE(r.Bounds().max().isApprox(Vector3d(10, 2, 6), 1e-12));
  MeshLoadOptions keep;
  keep.orient_outward = false;
  EXPECT_LT(LoadMesh(Path("io.ply"), keep).SignedVolume(), 0);
  MeshLoadOptions zero;
  zero.scale = 0;
  EXPECT_THROW(LoadMesh(Path("io.ply"), zero), OptionError);
}

TEST_F(MeshIoTest, MissingAndEmptyFiles) {
  const InputError none = LoadError(Path("absent.stl"));
  EXPECT_THAT(none.what(), HasSubstr("no such file"));
  const InputError empty = LoadError(Write("empty.obj", ""));
  EXPECT_THAT(empty.detail(), HasSubstr("empty"));
  EXPECT_THAT(LoadError(Write("nothing.obj", "# only a comment\n")).detail(), HasSubstr("no geometry"));
}

TEST_F(MeshIoTest, SaveRejectsUnknownFormatsAndBadMeshes) {
  TriangleMesh m = test::MakeBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  EXPECT_THROW(SaveMesh(m, Path("m.xyz")), std::invalid_argument);
  m.SetScalar("deviation", {1.0, 2.0});
  EXPECT_THROW(SaveMesh(m, Path("m.ply")), std::invalid_argument);
  m.vertex_scalars.clear();
  m.faces[0][0] = 99;
  EXPECT_THROW(SaveMesh(m, Path("m.obj")), std::invalid_argument);
  EXPECT_FALSE(fs::exists(Path("m.obj")));
}

TEST(MeshIo, IsMeshFile) {
  for (const char* yes : {"a.stl", "b.PLY", "c.obj", "d.off", "hull.stl.gz", "e.gltf", "f.glb", "g.dae", "h.3ds"}) {
    EXPECT_TRUE(IsMeshFile(yes)) << yes;
  }
  for (const char* no : {"a.csv", "b.json", "noext", "c.gz"}) EXPECT_FALSE(IsMeshFile(no)) << no;
}

// ---- the real hulls in ../shared/data ----------------------------------------------------

std::string SharedData(const std::string& name) { return std::string(HI_SHARED_DATA_DIR) + "/" + name; }
bool Present(const std::string& path) { return std::ifstream(path).good(); }

TEST(MeshIoSharedData, Dtmb5415) {
  const std::string path = SharedData("dtmb5415.stl.gz");
  if (!Present(path)) GTEST_SKIP() << "reference data absent: " << path;
  OrientationReport report;
  MeshLoadOptions o;
  o.orientation = &report;
  const TriangleMesh m = LoadMesh(path, o);
  EXPECT_EQ(m.faces.size(), 3436u);
  EXPECT_EQ(m.vertices.size(), 1720u);
  EXPECT_TRUE(report.closed);
  EXPECT_EQ(report.components, 1);
  EXPECT_GT(m.SignedVolume(), 0);
  EXPECT_NEAR(m.Bounds().sizes().x(), 153.23, 0.01);  // full scale, metres
}

TEST(MeshIoSharedData, DtcScaledToFullSize) {
  const std::string path = SharedData("dtc-hull-scaled.stl.gz");
  if (!Present(path)) GTEST_SKIP() << "reference data absent: " << path;
  OrientationReport report;
  MeshLoadOptions o;
  o.scale = 59.4;
  o.orientation = &report;
  const TriangleMesh m = LoadMesh(path, o);
  EXPECT_EQ(m.faces.size(), 116062u);
  EXPECT_TRUE(report.closed);
  const Vector3d size = m.Bounds().sizes();
  EXPECT_NEAR(size.x(), 372.77, 0.01);  // overall, bulb to rudder (Lpp is 355 m)
  EXPECT_NEAR(size.y(), 51.0, 0.01);    // beam
  EXPECT_NEAR(size.z(), 34.0, 0.01);
  EXPECT_GT(m.SignedVolume(), 0);
}

TEST(MeshIoSharedData, WigleyIsOpenAndOrientedOutward) {
  const std::string path = SharedData("wigley.stl.gz");
  if (!Present(path)) GTEST_SKIP() << "reference data absent: " << path;
  OrientationReport report;
  MeshLoadOptions o;
  o.orientation = &report;
  const TriangleMesh m = LoadMesh(path, o);
  EXPECT_EQ(m.faces.size(), 12896u);
  EXPECT_FALSE(report.closed);
  EXPECT_GT(report.boundary_edges, 0);
  // Away from the centre plane, normals point away from it.
  double side = 0;
  for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
    const Vector3d c = m.FaceCentroid(f);
    if (std::abs(c.y()) > 0.02) side += m.FaceArea(f) * m.face_normals[f].y() * (c.y() > 0 ? 1 : -1);
  }
  EXPECT_GT(side, 0);
}

TEST(MeshIoSharedData, GicpScanIsAPointCloud) {
  const std::string path = SharedData("gicp-source.ply");
  if (!Present(path)) GTEST_SKIP() << "reference data absent: " << path;
  EXPECT_EQ(LoadPointCloud(path).size(), 69792u);
  EXPECT_THROW(LoadMesh(path), InputError);
}

}  // namespace
}  // namespace hull
