/*---------------------------------------------------------------------------*\
  talusCaseInfo: print a one-line JSON summary of an OpenFOAM case's mesh.

  Usage (inside the case, or with -case DIR; add -parallel under mpirun for a
  decomposed case):

      talusCaseInfo -case DIR
      mpirun -n 2 talusCaseInfo -case DIR -parallel

  stdout carries exactly one JSON object and nothing else:

      {"openfoam": "v1912", "nCells": N, "nPoints": N,
       "bounds": [[xmin,ymin,zmin],[xmax,ymax,zmax]],
       "patches": [{"name": "...", "type": "...", "nFaces": N}, ...],
       "nProcs": P}

  All counts and the bounds are global (reduced over the processors);
  processor patches are left out. Everything OpenFOAM itself writes to stdout
  (banner, Info, warnings) is sent to stderr instead, so the DEM side can parse
  stdout directly. Errors exit non-zero with OpenFOAM's message on stderr.

  Part of Talus (foam-solvers/), GPL-3.0-or-later like OpenFOAM.
\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "polyMesh.H"
#include "SubField.H"
#include "globalMeshData.H"
#include "globalIndex.H"
#include "foamVersion.H"

#include <cstdio>
#include <cstdlib>
#include <unistd.h>

using namespace Foam;

// Shortest of %.15g..%.17g that reads back as the same double (0.1, not 0.10000000000000001).
static std::string number(double x)
{
    char buf[32];
    for (int digits = 15; digits <= 17; ++digits)
    {
        std::snprintf(buf, sizeof buf, "%.*g", digits, x);
        if (std::strtod(buf, nullptr) == x) break;
    }
    return buf;
}

static std::string vectorJson(const vector& v)
{
    return "[" + number(v.x()) + "," + number(v.y()) + "," + number(v.z()) + "]";
}

int main(int argc, char *argv[])
{
    // Keep a handle on the real stdout for the JSON, then point file descriptor 1 at stderr
    // so all of OpenFOAM's own output (it writes Info and warnings to stdout) ends up there.
    const int jsonFd = ::dup(STDOUT_FILENO);
    ::dup2(STDERR_FILENO, STDOUT_FILENO);

    argList::addNote("Print the mesh summary of a case as one JSON object on stdout");
    argList::noBanner();
    argList::noFunctionObjects();

    #include "setRootCase.H"
    #include "createTime.H"
    #include "createPolyMesh.H"

    // Global sizes. Points on processor boundaries exist on several ranks: mergePoints numbers
    // each of them once, so the size of its global numbering is the number of distinct points.
    const globalMeshData& global = mesh.globalData();
    const label nCells = global.nTotalCells();
    labelList pointToGlobal, uniquePoints;
    const label nPoints = global.mergePoints(pointToGlobal, uniquePoints)->size();
    const boundBox bounds(mesh.points(), true);  // true: reduced over the processors

    // Non-processor patches come first and are the same, in the same order, on every rank.
    const polyBoundaryMesh& patches = mesh.boundaryMesh();
    std::string patchJson;
    for (label patchi = 0; patchi < patches.nNonProcessor(); ++patchi)
    {
        const polyPatch& pp = patches[patchi];
        const label nFaces = returnReduce(pp.size(), sumOp<label>());
        // The patch's mean unit normal (area-weighted; its length is below 1 on a curved patch).
        const vectorField areas(pp.faceAreas());
        const vector area = returnReduce(Foam::sum(areas), sumOp<vector>());
        const scalar magArea = returnReduce(Foam::sum(Foam::mag(areas)), sumOp<scalar>());
        const vector normal = magArea > 0 ? area/magArea : vector::zero;
        // Patch names and types are OpenFOAM words: no quotes or backslashes to escape.
        patchJson += std::string(patchi ? ", " : "")
            + "{\"name\": \"" + pp.name() + "\", \"type\": \"" + pp.type()
            + "\", \"nFaces\": " + std::to_string(nFaces)
            + ", \"normal\": " + vectorJson(normal) + "}";
    }

    if (Pstream::master())
    {
        // The API of the loaded libOpenFOAM (1912): Debian's leaves foamVersion::version empty.
        const std::string json =
            "{\"openfoam\": \"v" + std::to_string(foamVersion::api) + "\""
          + ", \"nCells\": " + std::to_string(nCells)
          + ", \"nPoints\": " + std::to_string(nPoints)
          + ", \"bounds\": [" + vectorJson(bounds.min()) + ", " + vectorJson(bounds.max()) + "]"
          + ", \"patches\": [" + patchJson + "]"
          + ", \"nProcs\": " + std::to_string(Pstream::nProcs()) + "}\n";
        if (::write(jsonFd, json.data(), json.size()) != ssize_t(json.size()))
        {
            FatalErrorInFunction << "could not write to stdout" << exit(FatalError);
        }
    }
    ::close(jsonFd);

    return 0;
}
