// CGAL's exact Minkowski sum of two convex polytopes by spherical Gaussian
// maps (Fogel and Halperin; `Arr_polyhedral_sgm`, exact EPECK kernel): the
// peer of a DYMSUM update in issue 36's protocol (docs/BENCHMARKS.md, "DYMSUM
// against CGAL's Gaussian maps"), run by python/benchmarks/cgal/bench_sgm.py.
//
// Build (Debian/Ubuntu: apt-get install libcgal-dev; GPL, never linked into
// dymsum):
//   g++ -O2 -std=c++17 -DNDEBUG python/benchmarks/cgal/cgal_sgm.cpp \
//       -o target/cgal_sgm -lgmp -lmpfr
// Run: cgal_sgm P.off Q.off ROTATIONS [REPEATS]
//   P.off, Q.off: convex polytopes (OFF; vertices are doubles, taken exactly);
//   ROTATIONS: one rotation a line, nine doubles in row-major order.
// For each rotation R (the recomputation a static method pays per step):
//   1. P's vertices turned exactly: R v with every product and sum exact
//      (EPECK), not rounded to doubles;
//   2. P's Gaussian map built from the turned polyhedron (the initializer
//      of Arr_polyhedral_sgm);
//   3. that map overlaid with Q's, prepared once before the loop, by
//      `Arr_polyhedral_sgm::minkowski_sum`.
// Steps 1-3 are timed together, per rotation; the whole loop is repeated
// REPEATS times (default 1) and each rotation keeps its fastest time.
// Prints one JSON line: the median and mean seconds per step, the number of
// steps, and the sum's vertex count at the last step (its facets: a check
// against dymsum's facet count).
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Arr_spherical_gaussian_map_3/Arr_polyhedral_sgm.h>
#include <CGAL/Arr_spherical_gaussian_map_3/Arr_polyhedral_sgm_polyhedron_3.h>
#include <CGAL/Arr_spherical_gaussian_map_3/Arr_polyhedral_sgm_traits.h>
#include <CGAL/IO/Polyhedron_iostream.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_exact_constructions_kernel Kernel;
typedef Kernel::FT FT;
typedef Kernel::Point_3 Point_3;
typedef CGAL::Arr_polyhedral_sgm_traits<Kernel> Gm_traits;
typedef CGAL::Arr_polyhedral_sgm<Gm_traits> Gm;
typedef CGAL::Arr_polyhedral_sgm_polyhedron_3<Gm, Kernel> Gm_polyhedron;
typedef CGAL::Arr_polyhedral_sgm_initializer<Gm, Gm_polyhedron> Gm_initializer;

static bool read(const char* path, Gm_polyhedron& p) {
    std::ifstream in(path);
    if (!(in >> p) || p.empty() || !p.is_closed()) {
        std::fprintf(stderr, "cannot read a closed polyhedron from %s\n", path);
        return false;
    }
    return true;
}

// The facets of the sum: the vertices of its map of degree at least 3 (the
// map also has degree-2 vertices where arcs are split, e.g. on the
// parametrisation's identification curve).
static std::size_t facets_of(const Gm& gm) {
    std::size_t n = 0;
    for (auto v = gm.vertices_begin(); v != gm.vertices_end(); ++v) n += v->degree() >= 3;
    return n;
}

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s P.off Q.off ROTATIONS [REPEATS]\n", argv[0]);
        return 2;
    }
    Gm_polyhedron p, q;
    if (!read(argv[1], p) || !read(argv[2], q)) return 1;
    std::vector<std::array<double, 9>> rotations;
    {
        std::ifstream in(argv[3]);
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream s(line);
            std::array<double, 9> r;
            bool ok = true;
            for (double& x : r) ok = ok && static_cast<bool>(s >> x);
            if (ok) rotations.push_back(r);
        }
    }
    if (rotations.empty()) {
        std::fprintf(stderr, "no rotations in %s\n", argv[3]);
        return 1;
    }
    const int repeats = argc > 4 ? std::max(1, std::atoi(argv[4])) : 1;

    // Q's map, prepared once (Q does not move).
    Gm gq;
    Gm_initializer init_q(gq);
    init_q(q);
    if (std::getenv("SGM_DEBUG"))
        std::fprintf(stderr, "Q: %zu faces, map %zu vertices %zu edges %zu faces\n", q.size_of_facets(),
                     facets_of(gq), (size_t)gq.number_of_edges(), (size_t)gq.number_of_faces());
    // P's vertices, exact, in a fixed order.
    std::vector<Point_3> original;
    for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v) original.push_back(v->point());

    std::vector<double> best(rotations.size(), 1e300);
    std::size_t last_vertices = 0;
    for (int rep = 0; rep < repeats; ++rep) {
        for (std::size_t k = 0; k < rotations.size(); ++k) {
            const auto& r = rotations[k];
            Gm_polyhedron turned(p);
            auto t0 = std::chrono::steady_clock::now();
            std::size_t i = 0;
            for (auto v = turned.vertices_begin(); v != turned.vertices_end(); ++v, ++i) {
                const Point_3& a = original[i];
                v->point() = Point_3(FT(r[0]) * a.x() + FT(r[1]) * a.y() + FT(r[2]) * a.z(),
                                     FT(r[3]) * a.x() + FT(r[4]) * a.y() + FT(r[5]) * a.z(),
                                     FT(r[6]) * a.x() + FT(r[7]) * a.y() + FT(r[8]) * a.z());
            }
            Gm gp;
            Gm_initializer init_p(gp);
            init_p(turned);
            Gm sum;
            sum.minkowski_sum(gp, gq);
            auto t1 = std::chrono::steady_clock::now();
            best[k] = std::min(best[k], std::chrono::duration<double>(t1 - t0).count());
            // Vertices of the overlay: the facets of the sum.
            last_vertices = facets_of(sum);
        }
    }
    std::vector<double> sorted = best;
    std::sort(sorted.begin(), sorted.end());
    double mean = 0;
    for (double t : best) mean += t;
    mean /= best.size();
    std::printf("{\"median_seconds\": %.9g, \"mean_seconds\": %.9g, \"steps\": %zu, \"repeats\": %d, \"overlay_vertices\": %zu}\n",
                sorted[sorted.size() / 2], mean, best.size(), repeats, last_vertices);
    return 0;
}
