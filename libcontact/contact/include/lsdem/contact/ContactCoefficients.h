/// @file ContactCoefficients.h
/// @brief The coefficients of a contact law as a scene names them: the schema of a
///        [[contacts]] entry's numbers, which the scene reader, the scene writer, the Python
///        builder and docs/scenes.md share. Each sub-model contributes its own (the normal law
///        its stiffness, the shear springs theirs and friction, the dashpot the restitution),
///        with its meaning, range and default, how it is read from and set on a ContactModel,
///        and the rules between sub-models (checkContactModel). A new coefficient is one entry
///        here; every front end then reads, checks and writes it.
#pragma once

#include "lsdem/contact/ContactModel.h"
#include "lsdem/core/NumberRange.h"

#include <optional>
#include <string>
#include <vector>

namespace lsdem {

/// A rule a contact model breaks: the key it is about, what is wrong, the fix.
struct ContactProblem
{
    std::string key, problem, fix;
};

/// One number of a contact law.
struct ContactCoefficient
{
    std::string key;       ///< as scenes and Python's add_contact name it
    std::string subModel;  ///< "normal", "tangential" or "damping"
    NumberRange range;  ///< the values it may take
    std::optional<double> defaultValue;  ///< none: the scene must give it
    double (*get)(const ContactModel&);
    /// Set on @a model a value already in range.
    void (*set)(ContactModel&, double);
    /// Its unit in words where it depends on the model ("force/length³" for the adapted law's
    /// stiffness), noted beside it in written scenes; none for the others.
    std::string (*unit)(const ContactModel&) = nullptr;

    /// "> 0", ">= 0", "in (0, 1]".
    std::string rangeText() const;
    /// What is wrong with @a value for this coefficient ("must be > 0 (got -1)"), if anything.
    std::optional<ContactProblem> rangeProblem(double value) const;
    /// Whether a scene must write it to say what @a model holds: required, or not at its
    /// default.
    bool written(const ContactModel& model) const;
};

/// One named choice of a contact law (its formulation, node testing, quadrature): the schema of
/// a [[contacts]] entry's words, which the scene reader, the scene writer and Python's
/// add_contact share as they share the coefficients.
struct ContactChoice
{
    std::string key;                  ///< as scenes and Python's add_contact name it
    std::vector<std::string> values;  ///< the names it accepts, in the order messages list them
    std::string (*get)(const ContactModel&);
    /// Set on @a model the choice named @a value. @throw Error naming the accepted values.
    void (*set)(ContactModel&, const std::string& value);
    /// Whether a scene writes it always (the formulation, the testing: what a reader most
    /// needs to see) or only when not at its default (the quadrature).
    bool alwaysWritten = true;

    /// The default's name: what a ContactModel{} holds.
    std::string defaultValue() const { return get(ContactModel{}); }
    bool written(const ContactModel& model) const
    {
        return alwaysWritten || get(model) != defaultValue();
    }
};

/// Every choice, in the order a scene writes them: formulation, testing, quadrature.
const std::vector<ContactChoice>& contactChoices();

/// The choice named @a key. @throw std::out_of_range if there is none (a program error).
const ContactChoice& contactChoice(const std::string& key);

/// Every coefficient, sub-model by sub-model (normal, tangential, damping): the order a scene
/// writes them in.
const std::vector<ContactCoefficient>& contactCoefficients();

/// The coefficient named @a key. @throw std::out_of_range if there is none (a program error).
const ContactCoefficient& contactCoefficient(const std::string& key);

/// The default of the optional coefficient @a key. @throw std::out_of_range if @a key is not an
/// optional coefficient.
double contactCoefficientDefault(const std::string& key);

/// The first rule @a model breaks, if any: each coefficient's range, then the rules between
/// sub-models (shear springs need a law whose forces are per node; friction caps shear
/// springs, so it needs them; patch quadrature needs a traction per area). @a quote goes around formulation names in the fixes.
std::optional<ContactProblem> checkContactModel(const ContactModel& model,
                                                const std::string& quote = "");

} // namespace lsdem
