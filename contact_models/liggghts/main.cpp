// `liggghts` launcher: the stock LIGGGHTS driver, linked against the
// viscoelastic contact-model library so its models are registered.
#include <mpi.h>

#include "input.h"
#include "lammps.h"

int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    LAMMPS_NS::LAMMPS* lammps = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
    lammps->input->file();
    delete lammps;
    MPI_Finalize();
    return 0;
}
