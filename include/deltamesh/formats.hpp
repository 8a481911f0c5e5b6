// Exchange formats beyond Triangle's own: Gmsh .msh (4.1 and 2.2), VTK
// (.vtu XML and legacy .vtk), GeoJSON (written and read), OFF, and writing
// by file extension. See docs/formats.md for what each file contains.
//
// Every writer builds the file under a temporary name and renames it onto
// the target (io::AtomicFile), so a failure never leaves a partial file.
// Writers take a finished mesh: they write the live real triangles (dead and
// ghost slots are skipped) and every vertex, in vertex order, so vertex ids
// in the files are the mesh's (plus one where the format counts from 1).
//
// Quantities written per triangle, shared by all formats:
//  - region: triangle attribute 0 rounded to the nearest integer (the
//    regional attribute of -A), 0 when the mesh has no triangle attributes;
//  - min_angle: the smallest interior angle, in degrees;
//  - area: the (positive) area.
// Boundary edges are the edges with one triangle; segment edges are the
// constrained ones. Their marker is the segment's marker when nonzero,
// otherwise 1 on the mesh boundary and 0 inside (Triangle's -e rule).
#pragma once
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/svg.hpp"

namespace deltamesh {

struct BoundedVoronoi;  // voronoi.hpp

// Six-node (quadratic) triangles, the hook for Triangle's -o2: per live real
// triangle in output order, three extra vertex ids (mesh vertices) at the
// midpoints of the edges opposite corners 0, 1 and 2 -- Triangle's .ele
// order. Writers that support it reorder to their own convention.
struct SecondOrderNodes {
  std::span<const VertexId> midside;  // 3 per written triangle; empty: linear triangles
};

// ---------------------------------------------------------------------------
// Gmsh

enum class MshVersion {
  V41,  // MSH 4.1 ASCII (Gmsh >= 4.1): $Entities with one discrete curve per
        // boundary marker and one discrete surface per region
  V22,  // MSH 2.2 ASCII, for older readers (physical and elementary tags per element)
};

struct MshOptions {
  MshVersion version = MshVersion::V41;
  // Line elements (type 1) for the boundary and segment edges, grouped by
  // marker into 1-D physical groups "boundary_<marker>".
  bool boundary_lines = true;
  SecondOrderNodes second_order;  // type 9 triangles / type 8 lines when set
};

// Triangles (type 2) grouped by region into 2-D physical groups "region_<r>"
// ("domain" when the mesh has no triangle attributes); see docs/formats.md
// for how physical tags are chosen.
void write_msh(const Mesh& mesh, const std::string& path, const MshOptions& options = {});

// ---------------------------------------------------------------------------
// VTK

struct VtkOptions {
  // .vtu only: data arrays as base64-encoded raw binary instead of ASCII
  // (smaller and faster to load; ParaView and meshio read both).
  bool binary = false;
  SecondOrderNodes second_order;  // VTK_QUADRATIC_TRIANGLE (22) when set
};

// XML UnstructuredGrid. Cell data: region (Int32), min_angle, area (Float64)
// and attribute_<k> for every triangle attribute; point data: marker (Int32;
// the vertex markers, or 1 on the boundary and 0 elsewhere when the mesh has
// none) and attribute_<k> for every vertex attribute.
void write_vtu(const Mesh& mesh, const std::string& path, const VtkOptions& options = {});
// Legacy ASCII "DATASET UNSTRUCTURED_GRID" (file version 3.0), same fields.
void write_vtk(const Mesh& mesh, const std::string& path, const VtkOptions& options = {});

// ---------------------------------------------------------------------------
// GeoJSON (RFC 7946)

struct GeoJsonWriteOptions {
  bool triangles = true;  // one Polygon feature per triangle
  // Also one LineString feature per boundary or segment edge (kind
  // "segment", properties id, marker), for a boundary layer in GIS.
  bool segments = false;
  // Also one Polygon feature per bounded Voronoi cell (kind "voronoi_cell").
  const BoundedVoronoi* voronoi = nullptr;
};

// A FeatureCollection. Triangle features: Polygon [[a, b, c, a]]
// (counter-clockwise, as RFC 7946 asks for exterior rings) with properties
// kind "triangle", id (0-based output index), region, min_angle, area.
// Coordinates are written as they are in the mesh (shortest round-trip
// decimal); RFC 7946 means WGS 84 longitude/latitude, other coordinate
// systems must be assigned by the reader (QGIS: Layer CRS).
void write_geojson(const Mesh& mesh, const std::string& path, const GeoJsonWriteOptions& options = {});

// A syntax or structure error in a JSON / GeoJSON file, with the 1-based
// column (in characters) as well as the line. what() reads
// "file:line:column: problem".
class JsonParseError : public ParseError {
 public:
  JsonParseError(std::string file, std::size_t line, std::size_t column, const std::string& problem);
  std::size_t column() const { return column_; }
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::size_t column_;
  std::string message_;
};

struct GeoJsonReadOptions {
  // Name of a feature property that becomes the regional attribute of each
  // of the feature's polygons (one RegionSeed per polygon). Numbers (and
  // booleans, as 0/1) are used as they are; strings are numbered 1, 2, ... in
  // order of first appearance (GeoJsonInfo::categories); a missing or null
  // property gives no seed. Empty: no seeds.
  std::string attribute_property;
  // Name of a numeric feature property giving a maximum triangle area per
  // polygon (RegionSeed::max_area). Empty: none.
  std::string area_property;
  // Name of an integer feature property used as the boundary marker of the
  // feature's ring segments; when empty or absent, outer rings get
  // `outer_marker` and holes `hole_marker`.
  std::string marker_property;
  int outer_marker = 1;
  int hole_marker = 1;
};

struct GeoJsonInfo {
  std::size_t features = 0;
  std::size_t polygons = 0;            // Polygon geometries, MultiPolygon parts counted one each
  std::size_t rings = 0;               // rings turned into segment chains
  std::size_t holes = 0;               // of which interior rings
  std::size_t skipped_geometries = 0;  // Point, LineString, ... and null geometries: ignored
  std::size_t unclosed_rings = 0;      // last position != first: closed implicitly
  std::size_t degenerate_rings = 0;    // fewer than 3 distinct positions: ignored
  std::size_t duplicate_points = 0;    // positions equal to an earlier vertex, merged
  std::size_t duplicate_segments = 0;  // the same edge on two rings (shared borders), kept once
  std::size_t seeds = 0;               // region seeds produced
  std::size_t seeds_failed = 0;        // polygons where no interior point was found
  std::size_t polygons_with_attribute = 0;  // polygons whose feature has attribute_property (not null)
  std::size_t polygons_with_area = 0;       // ... area_property
  std::vector<std::string> categories; // string attribute values; value i has attribute i+1
};

// Polygons and MultiPolygons, bare or inside Feature, FeatureCollection and
// GeometryCollection wrappers, as a Pslg to mesh with FillRule::EvenOdd:
// every ring (outer or hole) becomes a closed chain of segments, the
// duplicate closing position dropped; positions with exactly equal x and y
// are merged into one vertex; an edge shared by two rings is one segment.
// Extra coordinates (z) are ignored. Holes need no hole points: even-odd
// removes them, and it makes adjacent polygons (shared borders) one domain
// with a segment between them.
//
// Region seeds (attribute_property / area_property): one per polygon, at an
// interior point that is inside the outer ring and outside every hole of
// that polygon, found on a horizontal scanline through the polygon (the
// middle of the widest inside interval on the scanlines between distinct
// vertex heights). Where polygons overlap, the seed of the later polygon
// wins for the piece it lies in (carve_domain's rule).
//
// Throws JsonParseError (file, line, column) for malformed JSON and for
// GeoJSON structure it cannot use (a missing "type", "coordinates" or
// "features", a position that is not an array of 2 or 3 numbers, numbers
// out of range, an unknown "type"). Some slips that RFC 7946 forbids are
// accepted and counted in GeoJsonInfo instead: unclosed rings (closed
// implicitly) and rings of fewer than 3 distinct positions (ignored).
Pslg read_geojson(const std::string& path, const GeoJsonReadOptions& options = {}, GeoJsonInfo* info = nullptr);
// The same from text in memory; `name` is used in error messages.
Pslg parse_geojson(std::string_view text, const std::string& name = "<geojson>",
                   const GeoJsonReadOptions& options = {}, GeoJsonInfo* info = nullptr);

// ---------------------------------------------------------------------------
// OFF (Geomview Object File Format; Triangle's -g)

// "OFF", counts, every vertex as x y 0, every triangle as "3 a b c" (0-based).
void write_off(const Mesh& mesh, const std::string& path);

// ---------------------------------------------------------------------------
// Writing by extension

enum class OutputFormat { Msh, Vtu, Vtk, Svg, GeoJson, Off, Node, Ele, Edge, Neigh, Poly };

// The format a path's extension names (case-insensitive: .msh .vtu .vtk .svg
// .geojson/.json .off .node .ele .edge .neigh .poly), or nullopt.
std::optional<OutputFormat> output_format_for(std::string_view path);
std::string_view to_string(OutputFormat format);

struct OutputOptions {
  MshOptions msh;
  VtkOptions vtk;
  SvgOptions svg;
  GeoJsonWriteOptions geojson;  // its voronoi pointer (and svg's) is overridden by `voronoi` when that is set
  int first_index = 0;          // Triangle formats: numbering
  bool write_markers = true;    // Triangle formats: markers (-B turns them off)
  // Bounded Voronoi cells for the SVG overlay and the GeoJSON cells (nullptr: none).
  const BoundedVoronoi* voronoi = nullptr;
};

// Writes `mesh` to `path` in the format its extension names. Throws
// UnknownOutputFormat when the extension names none (before creating any file).
void write_output(const Mesh& mesh, const std::string& path, const OutputOptions& options = {});

class UnknownOutputFormat : public Error {
 public:
  explicit UnknownOutputFormat(const std::string& path)
      : Error("cannot tell the output format of '" + path +
              "' from its extension (known: .msh .vtu .vtk .svg .geojson .json .off .node .ele .edge .neigh .poly)"),
        path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace deltamesh
