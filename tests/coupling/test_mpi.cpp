// MPI works as the coupling needs it: two ranks, collectives and point-to-point messages of
// particle-sized payloads. Run under mpirun -n 2 (see tests/CMakeLists.txt).
#include <mpi.h>

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

TEST(CouplingMpi, TwoRanksExchangeParticleArrays)
{
  int rank = -1, size = -1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2);

  // Rank 0 sends 1000 particles x 10 doubles in one message; rank 1 returns 6 per particle.
  const int particles = 1000;
  if (rank == 0)
  {
    std::vector<double> state(10 * particles);
    std::iota(state.begin(), state.end(), 0.0);
    MPI_Send(state.data(), static_cast<int>(state.size()), MPI_DOUBLE, 1, 0, MPI_COMM_WORLD);
    std::vector<double> forces(6 * particles);
    MPI_Recv(forces.data(), static_cast<int>(forces.size()), MPI_DOUBLE, 1, 1, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    for (int p = 0; p < particles; ++p)
      EXPECT_EQ(forces[6 * p], 2.0 * state[10 * p]);
  }
  else
  {
    std::vector<double> state(10 * particles);
    MPI_Recv(state.data(), static_cast<int>(state.size()), MPI_DOUBLE, 0, 0, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    std::vector<double> forces(6 * particles);
    for (int p = 0; p < particles; ++p)
      forces[6 * p] = 2.0 * state[10 * p];
    MPI_Send(forces.data(), static_cast<int>(forces.size()), MPI_DOUBLE, 0, 1, MPI_COMM_WORLD);
  }

  double local = rank + 1.0, total = 0.0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(total, 3.0);
}

int main(int argc, char** argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // Only rank 0 prints, so ctest's log is readable; every rank's failure still fails the run.
  if (rank != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
        ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  int failed = RUN_ALL_TESTS();
  int any_failed = 0;
  MPI_Allreduce(&failed, &any_failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any_failed;
}
