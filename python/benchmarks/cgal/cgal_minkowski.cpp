// CGAL's exact Minkowski sum of two closed polyhedra (Nef polyhedra, convex
// decomposition inside CGAL), the peer of python/benchmarks/bench_nonconvex.py.
//
// Build (Debian/Ubuntu: apt-get install libcgal-dev; GPL, never linked into
// dymsum):
//   g++ -O2 -std=c++17 -DNDEBUG python/benchmarks/cgal/cgal_minkowski.cpp \
//       -o target/cgal_minkowski -lgmp -lmpfr
// Run: cgal_minkowski A.off B.off [OUT.off]
// Prints one JSON line: seconds (Nef construction of both operands and
// minkowski_sum_3, not the file reading), volume, vertices, triangles.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/IO/Polyhedron_iostream.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/minkowski_sum_3.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

typedef CGAL::Exact_predicates_exact_constructions_kernel K;
typedef CGAL::Polyhedron_3<K> Polyhedron;
typedef CGAL::Nef_polyhedron_3<K> Nef;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

static bool read(const char* path, Polyhedron& p) {
    std::ifstream in(path);
    if (!(in >> p) || p.empty() || !p.is_closed()) {
        std::fprintf(stderr, "cannot read a closed polyhedron from %s\n", path);
        return false;
    }
    return true;
}

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s A.off B.off [OUT.off]\n", argv[0]);
        return 2;
    }
    Polyhedron pa, pb;
    if (!read(argv[1], pa) || !read(argv[2], pb)) return 1;
    auto t0 = std::chrono::steady_clock::now();
    Nef na(pa), nb(pb);
    Nef sum = CGAL::minkowski_sum_3(na, nb);
    auto t1 = std::chrono::steady_clock::now();
    Mesh m;
    CGAL::convert_nef_polyhedron_to_polygon_mesh(sum, m, true);
    double volume = CGAL::to_double(CGAL::Polygon_mesh_processing::volume(m));
    std::printf("{\"seconds\": %.6f, \"volume\": %.17g, \"vertices\": %zu, \"triangles\": %zu}\n",
                std::chrono::duration<double>(t1 - t0).count(), volume,
                (size_t)m.number_of_vertices(), (size_t)m.number_of_faces());
    if (argc > 3) {
        std::ofstream out(argv[3]);
        out.precision(17);
        CGAL::IO::write_OFF(out, m);
    }
    return 0;
}
