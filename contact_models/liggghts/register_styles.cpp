// Adds `model viscoelastic` and `tangential pournin` to the contact-model
// factories of an installed libliggghts when this library is loaded (linked
// into our `liggghts` launcher, or LD_PRELOADed into the stock one).
//
// LIGGGHTS instantiates one pair style and one wall per model combination;
// its generic fallback only knows the models compiled into it. So every
// combination we support is instantiated here, and every other combination
// that names one of our models gets a creator that stops with an ERROR
// listing the supported ones.
#include "fix_insert_stream.h"  // pair_gran_base.h uses it without including it

#include <sstream>
#include <string>

#include "contact_models.h"
#include "error.h"
#include "fix_wall_gran_base.h"
#include "granular_pair_style.h"
#include "granular_wall.h"
#include "pair_gran_base.h"

namespace {

using namespace LIGGGHTS;
using namespace LIGGGHTS::ContactModels;

template<int T>
using Style = GranStyle<VISCOELASTIC, T, COHESION_OFF, ROLLING_OFF, SURFACE_DEFAULT>;

// `tangential no_history` has no spring: the tangential coefficients that
// exactRestitution solves (and the log reports) would not be applied, so the
// collision would restitute neither its et nor what the log says (-0.21 for
// a requested 0.46). Stopped where the settings are read.
template<class Base>
struct WithoutSpring : Base {
    template<class Parent>
    WithoutSpring(LAMMPS_NS::LAMMPS* lmp, Parent* parent, int64_t hash) : Base(lmp, parent, hash), lmp_(lmp)
    {}
    void settings(int nargs, char** args, IContactHistorySetup* hsetup) override
    {
        for (int i = 0; i + 1 < nargs; ++i)
            if (std::string(args[i]) == "exactRestitution" && std::string(args[i + 1]) == "on")
                lmp_->error->all(FLERR, "model viscoelastic tangential no_history: exactRestitution on solves the "
                                        "tangential spring's coefficients, and no_history has no spring (a dashpot "
                                        "only); use tangential history or pournin, or exactRestitution off");
        Base::settings(nargs, args, hsetup);
    }
    LAMMPS_NS::LAMMPS* lmp_;
};

template<int T>
PairStyles::IGranularPairStyle* createPair(LAMMPS_NS::LAMMPS* lmp, LAMMPS_NS::PairGran* parent, int64_t hash)
{
    using Pair = PairStyles::Granular<ContactModel<Style<T> > >;
    if constexpr (T == TANGENTIAL_NO_HISTORY) return new WithoutSpring<Pair>(lmp, parent, hash);
    else return new Pair(lmp, parent, hash);
}

template<int T>
Walls::IGranularWall* createWall(LAMMPS_NS::LAMMPS* lmp, LAMMPS_NS::FixWallGran* parent, int64_t hash)
{
    using Wall = Walls::Granular<ContactModel<Style<T> > >;
    if constexpr (T == TANGENTIAL_NO_HISTORY) return new WithoutSpring<Wall>(lmp, parent, hash);
    else return new Wall(lmp, parent, hash);
}

// One supported combination: `model viscoelastic tangential <name>`. `own`:
// the tangential model is this library's (libliggghts must learn its name).
struct Combination {
    const char* tangentialName;
    int tangential;
    bool own;
    int64_t hash;
    PairStyles::IGranularPairStyle* (*pair)(LAMMPS_NS::LAMMPS*, LAMMPS_NS::PairGran*, int64_t);
    Walls::IGranularWall* (*wall)(LAMMPS_NS::LAMMPS*, LAMMPS_NS::FixWallGran*, int64_t);
};

template<int T>
constexpr Combination combination(const char* tangentialName, bool own = false)
{
    return {tangentialName, T, own, Style<T>::HASHCODE, &createPair<T>, &createWall<T>};
}

// What this build supports: `model viscoelastic` with one of these
// tangential models (cohesion off, rolling_friction off, surface default).
// The model names, the factories, the check and the ERROR listing them all
// come from here: adding a combination is one line.
constexpr Combination kSupported[] = {
    combination<TANGENTIAL_HISTORY>("history"),
    combination<TANGENTIAL_POURNIN>("pournin", true),
    combination<TANGENTIAL_NO_HISTORY>("no_history"),
};

bool isSupported(int64_t hash)
{
    for (const Combination& c : kSupported)
        if (hash == c.hash) return true;
    return false;
}

bool isOwnTangential(int t)
{
    for (const Combination& c : kSupported)
        if (c.own && c.tangential == t) return true;
    return false;
}

std::string supportedList()
{
    std::ostringstream s;
    s << "this build supports the viscoelastic law only as";
    const char* separator = " ";
    for (const Combination& c : kSupported) {
        s << separator << "'model viscoelastic tangential " << c.tangentialName << "'";
        separator = ", ";
    }
    s << " (cohesion, rolling_friction and surface models off / default)";
    return s.str();
}

template<typename Parent, typename Interface>
Interface* rejectCombination(LAMMPS_NS::LAMMPS* lmp, Parent*, int64_t)
{
    const std::string msg = "Unsupported granular model combination: " + supportedList();
    lmp->error->all(FLERR, msg.c_str());
    return NULL;
}

std::vector<int> ids(const char* kind)
{
    std::vector<int> v;
    if (std::string(kind) == "normal") {
        v.push_back(NORMAL_OFF);
#define NORMAL_MODEL(ID, NAME, CONST) v.push_back(CONST);
#include "style_normal_model.h"
#undef NORMAL_MODEL
    } else if (std::string(kind) == "tangential") {
        v.push_back(TANGENTIAL_OFF);
#define TANGENTIAL_MODEL(ID, NAME, CONST) v.push_back(CONST);
#include "style_tangential_model.h"
#undef TANGENTIAL_MODEL
    } else if (std::string(kind) == "cohesion") {
        v.push_back(COHESION_OFF);
#define COHESION_MODEL(ID, NAME, CONST) v.push_back(CONST);
#include "style_cohesion_model.h"
#undef COHESION_MODEL
    } else if (std::string(kind) == "rolling") {
        v.push_back(ROLLING_OFF);
#define ROLLING_MODEL(ID, NAME, CONST) v.push_back(CONST);
#include "style_rolling_model.h"
#undef ROLLING_MODEL
    } else {
#define SURFACE_MODEL(ID, NAME, CONST) v.push_back(CONST);
#include "style_surface_model.h"
#undef SURFACE_MODEL
    }
    return v;
}

struct Registrar {
    Registrar()
    {
        ContactModels::Factory& models = ContactModels::Factory::instance();
        models.addNormalModel("viscoelastic", VISCOELASTIC);
        for (const Combination& c : kSupported)
            if (c.own) models.addTangentialModel(c.tangentialName, c.tangential);

        PairStyles::Factory& pairs = PairStyles::Factory::instance();
        Walls::Factory& walls = Walls::Factory::instance();
        for (const Combination& c : kSupported) {
            pairs.addStyle("gran", c.hash, c.pair);
            walls.addStyle("gran", c.hash, c.wall);
        }

        // every other combination naming one of our models stops with the list above
        for (int n : ids("normal"))
            for (int t : ids("tangential")) {
                if (n != VISCOELASTIC && !isOwnTangential(t)) continue;
                for (int c : ids("cohesion"))
                    for (int r : ids("rolling"))
                        for (int s : ids("surface")) {
                            const int64_t hash = Utils::generate_gran_hashcode(n, t, c, r, s);
                            if (isSupported(hash)) continue;
                            pairs.addStyle("gran", hash,
                                           &rejectCombination<LAMMPS_NS::PairGran, PairStyles::IGranularPairStyle>);
                            walls.addStyle("gran", hash,
                                           &rejectCombination<LAMMPS_NS::FixWallGran, Walls::IGranularWall>);
                        }
            }
    }
};

const Registrar registrar;

}  // namespace
