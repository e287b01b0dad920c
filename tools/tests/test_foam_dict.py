"""tools/foam_dict.py: entries changed as `foamDictionary -entry -set` changes them (the
rest of the text kept to the character), and OpenFOAM's ascii lists read as DPMFoam writes
them."""
import numpy as np
import pytest

import foam_dict

CLOUD = """FoamFile
{
    version 2.0; format ascii; class dictionary; object kinematicCloudProperties;
}
// a comment { with braces }
solution
{
    active          true;   // trailing comment
    interpolationSchemes { U.air cellPoint; }
}
subModels
{
    particleForces { ErgunWenYuDrag; gravity; }
    pairCollisionCoeffs
    {
        pairSpringSliderDashpotCoeffs
        {
            alpha               0.02;
            mu                  0.10;
        }
        mu 0.5;
    }
}
"""


def test_a_nested_value_is_replaced_and_nothing_else_changes():
    path = "subModels/pairCollisionCoeffs/pairSpringSliderDashpotCoeffs/mu"
    changed = foam_dict.set_entry(CLOUD, path, "0.3")
    assert foam_dict.get_entry(changed, path) == "0.3"
    assert changed == CLOUD.replace("mu                  0.10;", "mu                  0.3;")
    # the same keyword one level up is another entry
    assert foam_dict.get_entry(changed, "subModels/pairCollisionCoeffs/mu") == "0.5"


def test_comments_and_inline_dictionaries_do_not_confuse_the_path():
    assert foam_dict.get_entry(CLOUD, "solution/active") == "true"
    assert foam_dict.get_entry(CLOUD, "solution/interpolationSchemes/U.air") == "cellPoint"
    with pytest.raises(KeyError):
        foam_dict.get_entry(CLOUD, "comment")


def test_the_entry_after_a_directive_is_found():
    text = '#include "porousParameters"\n\nsolution\n{\n    coupled true;\n}\n'
    assert foam_dict.get_entry(text, "solution/coupled") == "true"
    changed = foam_dict.set_entry(text, "solution/sourceTerms", "{ schemes { U semiImplicit 1; } }")
    assert foam_dict.get_entry(changed, "solution/sourceTerms/schemes/U") == "semiImplicit 1"


def test_a_missing_entry_is_added_to_its_dictionary_and_a_missing_parent_refused():
    changed = foam_dict.set_entry(CLOUD, "solution/coupled", "true")
    assert foam_dict.get_entry(changed, "solution/coupled") == "true"
    assert foam_dict.get_entry(changed, "solution/active") == "true"
    with pytest.raises(KeyError):
        foam_dict.set_entry(CLOUD, "nothing/here", "1")
    with pytest.raises(ValueError):
        foam_dict.set_entry(CLOUD, "subModels/particleForces", "x")


def test_lists_as_dpmfoam_writes_them():
    header = "FoamFile { class vectorField; }\n"
    positions = header + "3\n(\n(1 2 3) 0\n(-1e-3 2.5 0) 4\n(0 0 7.5e+2) 1\n)\n"
    assert np.array_equal(foam_dict.read_list(positions, 3),
                          [[1, 2, 3], [-1e-3, 2.5, 0], [0, 0, 750]])
    assert np.array_equal(foam_dict.read_list(header + "2{0.0025}\n", 1), [0.0025, 0.0025])
    assert np.array_equal(foam_dict.read_list(header + "3\n(\n0\n2\n1\n)\n", 1), [0, 2, 1])
    with pytest.raises(ValueError):
        foam_dict.read_list(header + "3\n(\n0\n2\n)\n", 1)


def test_internal_fields_uniform_and_not():
    field = ("FoamFile { class volScalarField; }\ndimensions [0 2 -2 0 0 0 0];\n"
             "internalField nonuniform List<scalar> 3\n(\n1.5\n-2\n3e-1\n)\n;\n"
             "boundaryField { top { type fixedValue; value uniform 0; } }\n")
    assert np.array_equal(foam_dict.read_internal_field(field, 3), [1.5, -2, 0.3])
    uniform = "FoamFile { }\ninternalField uniform (0 0 1.875);\nboundaryField { }\n"
    assert foam_dict.read_internal_field(uniform, 2).tolist() == [[0, 0, 1.875]] * 2


def test_an_added_dictionary_entry_has_no_semicolon_and_keeps_the_indentation():
    text = "a\n{\n    b\n    {\n        c;\n    }\n}\n"
    out = foam_dict.set_entry(text, "a/b/paper", "{}")
    assert out == "a\n{\n    b\n    {\n        c;\n        paper {}\n    }\n}\n"
    out = foam_dict.set_entry(text, "top", "{ form paper; }")
    assert out.endswith("\ntop { form paper; }\n")
    assert foam_dict.set_entry(text, "a/b/x", "1").count("        x 1;\n    }") == 1
