# Writes the malformed parser corpus (run from tests/parser_corpus/malformed/): each text marks with @@ where the error must point.
import os, gzip
H = "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n}\n"
cases = {
 "missing_semicolon_eof": (H+"a 1;\nnu 0.01@@", "expected ';' to end the entry 'nu'"),
 "missing_semicolon_before_brace": (H+"d\n{\n    type wall@@\n}\n", "expected ';' to end the entry 'type'"),
 "missing_semicolon_then_dict": (H+"a 1\nb { c 1; }@@\n", "expected ';' to end the entry 'a'"),
 "unclosed_dict": (H+"d\n{\n    a 1;\n@@", "expected '}' to close the dictionary opened at line 8"),
 "stray_close_brace": (H+"a 1;\n@@}\n", "found '}' with no dictionary open"),
 "unclosed_list": (H+"v (1 2 3@@;\n", "expected ')' to close the list opened at line 7 column 3, found ';'"),
 "unclosed_list_eof": (H+"v (1 2\n  (3 4)\n@@", "expected ')' to close the list opened at line 7 column 3, found the end of the file"),
 "unclosed_list_in_dict": (H+"d\n{\n    v (1 2\n@@}\n", "expected ')' to close the list opened at line 9 column 7, found '}'"),
 "stray_close_paren": (H+"v 1 @@);\n", "found ')' with no list open"),
 "stray_close_bracket": (H+"v 1 @@];\n", "found ']' with no dimension set open"),
 "unclosed_string": (H+"s @@\"abc;\nt 1;\n", "expected '\"' to close the string opened here"),
 "unclosed_quoted_key": (H+"@@\"(top|bottom) { type wall; }\n", "expected '\"' to close the string opened here"),
 "unclosed_comment": (H+"a 1;\n@@/* a comment\nb 2;\n", "expected '*/' to close the comment opened here"),
 "unclosed_code": (H+"code @@#{ int x = 1;\n", "expected '#}' to close the code block opened here"),
 "unclosed_eval": (H+"x #eval@@{ 1 + 2 ;\n", "expected '}' to close the expression opened here"),
 "count_mismatch": (H+"l @@3((0 0 0)(1 1 1));\n", "expected 3 elements as the count says, found a list of 2"),
 "count_mismatch_top_level": (H+"@@4\n(\n(0 0 0)\n)\n", "expected 4 elements as the count says, found a list of 1"),
 "count_mismatch_nonuniform": (H+"internalField nonuniform List<scalar> @@5(1 2 3);\n", "expected 5 elements as the count says, found a list of 3"),
 "uniform_list_unclosed": (H+"l 3{0.5 @@;\n", "expected '}' to end the uniform list N{value}"),
 "uniform_list_empty": (H+"l 3{@@};\n", "expected the value of the uniform list N{value}"),
 "undefined_variable": (H+"a @@$b;\n", "undefined variable '$b'"),
 "undefined_parent_variable": (H+"d { x 1; }\ne { y @@$..x; }\n", "undefined variable '$..x'"),
 "undefined_top_scoped_variable": (H+"d { y 1; }\na @@$:d.x;\n", "undefined variable '$:d.x'"),
 "variable_defined_later": (H+"a @@$b;\nb 1;\n", "undefined variable '$b'"),
 "merge_non_dictionary": (H+"a 1;\nd { @@$a; }\n", "expected '$a' to name a dictionary to merge here"),
 "dollar_without_name": (H+"a @@$;\n", "expected a variable name after '$'"),
 "unclosed_braced_variable": (H+"a @@${b;\n", "expected '}' to close '${'"),
 "hash_without_name": (H+"a @@# ;\n", "expected a directive name after '#'"),
 "unknown_directive": (H+"@@#frobnicate \"x\"\n", "unknown directive '#frobnicate'"),
 "missing_include": (H+"a 1;\n@@#include \"doesNotExist\"\n", "cannot include \"doesNotExist\": file not found"),
 "keyword_expected": (H+"d { @@(1 2); }\n", "expected a keyword or '}', found '('"),
 "dimension_count": (H+"nu [@@0 2 -1] 0.01;\n", "expected 5 or 7 dimension exponents, found 3"),
 "unclosed_dimensions": (H+"nu [0 2 -1 0 0 0 0@@;\n", "expected ']' to close the dimension set opened here"),
 "single_quote": (H+"a @@'x';\n", "expected a value, found '''"),
 "too_deep": (H+"a " + "("*200 + "@@" + "("*50 + "\n", "nested lists and dictionaries"),
}
def write(name, text, msg, file=None, raw=None):
    pos = text.index("@@")
    before = text[:pos]
    line = before.count("\n") + 1
    col = len(before.split("\n")[-1]) + 1
    body = (text[:pos] + text[pos+2:]).encode()
    if raw: body = raw(body)
    open(name, "wb").write(body)
    with open(name + ".expect", "w") as f:
        f.write(f"{line} {col}\n{msg}\n")
        if file: f.write(f"file {file}\n")
for name, (text, msg) in cases.items():
    write(name, text, msg)
# An error inside an included file names the included file.
open("fragment_with_error.inc", "w").write("// included by include_with_error\nx 1;\ny 2\n")
open("include_with_error", "w").write(H+"#include \"fragment_with_error.inc\"\n")
with open("include_with_error.expect", "w") as f:
    f.write("3 4\nexpected ';' to end the entry 'y'\nfile fragment_with_error.inc\n")
# A file that includes itself.
write("include_cycle", "@@#include \"include_cycle\"\n", "nested #include")
# Invalid UTF-8: the error points at the first bad byte.
write("invalid_utf8", H+"a 1;\nb @@X;\n", "expected UTF-8 text",
      raw=lambda b: b.replace(b"X;", b"\xff;"))
# Gzip magic bytes, then a truncated stream: a whole-file error (line 0, column 0).
data = gzip.compress((H+"a 1;\n").encode(), mtime=0)[:20]
open("truncated.gz", "wb").write(data)
open("truncated.gz.expect", "w").write("0 0\ncannot decompress gzip data\n")
