package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.Diagnostic;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

/**
 * Clocks as Uppaal 5 treats them in statistical model checking, and their kin: clocks with initial values,
 * clocks in arithmetic on doubles and passed as doubles, clocks set to doubles and to other clocks, rates given
 * by clocks, clock guards on urgent channels, the built-in constants ({@code M_PI}, {@code INT16_MAX},
 * {@code int8_t}), {@code ==} on arrays and structs, external functions with aliases and string arguments. Each
 * loads, type-checked with Uppaal's rules, and says why a run is refused; each misuse is an error at its place.
 * Every model was written for this test; positions were counted by hand.
 */
class HybridClockTest {
    private static final String XTA = "m.xta";

    private static Network load(String text) throws ModelException {
        return ModelLoader.load(XTA, text);
    }

    /** The one error of a model that must be rejected, as "line:column: message". */
    private static String error(String text) {
        ModelException e = assertThrows(ModelException.class, () -> load(text));
        assertEquals(1, e.errors().size(), e::getMessage);
        Diagnostic d = e.errors().get(0);
        return d.line() + ":" + d.column() + ": " + d.message();
    }

    /** A process with one edge from A to A with {@code labels}, after {@code globals}. */
    private static String edge(String globals, String labels) {
        return globals + "\nprocess P() { state A; init A; trans A -> A { " + labels + " }; }\nsystem P;\n";
    }

    /** The reason a run is refused that starts with {@code feature}, as "line:column: message". */
    private static String refusal(Network n, String feature) {
        Diagnostic d = n.startErrors().stream().filter(s -> s.message().startsWith(feature)).findFirst()
                .orElseThrow(() -> new AssertionError(feature + " in " + n.startErrors()));
        return d.line() + ":" + d.column() + ": " + d.message();
    }

    @Test
    void aModelWithEveryConstructLoadsAndSaysWhyItCannotRun() throws ModelException {
        Network n = ModelLoader.loadResource(HybridClockTest.class.getClassLoader(),
                "io/dtron/model/fidelity/hybrid.xml");
        assertEquals(5, n.clockCount(), "x, y, h and xs[2]: " + n.clocks());
        Map<String, String> features = Map.of(
                "a clock with an initial value", "5:11",
                "a clock used as a real number", "15:26",
                "a clock rate given by a clock or a real number", "21:43",
                "a clock guard on an edge that synchronises on an urgent channel", "30:39",
                "a clock set to a real number or to another clock", "32:42",
                "'==' and '!=' on arrays and structs", "37:38",
                "the external function 'gain' of \"libcontrol.so\"", "38:47");
        for (Map.Entry<String, String> f : features.entrySet()) {
            Diagnostic d = n.startErrors().stream().filter(s -> s.message().startsWith(f.getKey())).findFirst()
                    .orElseThrow(() -> new AssertionError(f.getKey() + " in " + n.startErrors()));
            assertEquals(f.getValue(), d.line() + ":" + d.column(), d::format);
            assertTrue(d.message().contains(" cannot be run by DTRON's engine: "), d::format);
            assertTrue(n.warnings().stream().anyMatch(w -> w.pos() == d.pos()
                    && w.message().endsWith("'dtron run' refuses it")), () -> "check warns of " + d.format());
        }
        Diagnostic guard = n.startErrors().stream().filter(s -> s.message().startsWith("a clock guard")).findFirst()
                .orElseThrow();
        assertTrue(guard.format().endsWith("(template Heater, guard label, column 1)"), guard::format);
    }

    // ================================================================ clocks with initial values

    @Test
    void clocksAndArraysOfClocksTakeInitialValuesComputableAtCompileTime() throws ModelException {
        Network n = load(edge("const int K = 2;\nclock x = 2.5, y = K * 2, z = 0;\nclock xs[3] = {1.0, K, M_PI};", ""));
        assertEquals(6, n.clockCount(), "x, y, z, xs[3]");
        assertEquals("2:11: a clock with an initial value cannot be run by DTRON's engine: the engine starts every"
                + " clock at 0, as the zones of symbolic model checking do", refusal(n, "a clock with"));
    }

    @Test
    void aClockInitialisedToZeroStartsWhereEveryClockStarts() throws ModelException {
        Network n = load(edge("clock x = 0;\nclock xs[2] = {0, 0};", ""));
        assertTrue(n.startErrors().isEmpty(), () -> n.startErrors().toString());
    }

    @Test
    void aClockInitialisedFromAVariableOrAClockIsNotComputableAtCompileTime() {
        assertEquals("2:11: the initial value of clock 'y' must be computable at compile time",
                error(edge("clock x;\nclock y = x;", "")));
        assertEquals("2:11: the initial value of clock 'y' must be computable at compile time",
                error(edge("int i = 3;\nclock y = i;", "")));
        assertEquals("1:15: clock 'xs' has 2 elements, but the initialiser gives 3",
                error(edge("clock xs[2] = {1, 2, 3};", "")));
        assertEquals("1:1: 'const' does not apply to clocks", error(edge("const clock c = 1;", "")));
        assertEquals("1:1: 'meta' does not apply to clocks", error(edge("meta clock c;", "")));
        assertEquals("2:11: clock 'x' is a clock and cannot be initialised with an array (int[3])",
                error(edge("const int a[3] = {1, 2, 3};\nclock x = a;", "")));
    }

    // ================================================================ clocks as real numbers

    @Test
    void clocksInArithmeticOnDoublesAndAsDoubleArguments() throws ModelException {
        Network n = load(edge("""
                clock x, y;
                double d;
                double scale(double v) { return v * 2.0; }
                void step() { double e = x * 2.0; d = sqrt(x) + fabs(x - y) + scale(y) + e + (5 - x) + -y; }""",
                "guard x * 2 < 3; assign step(), d = x + y;"));
        assertEquals("4:26: a clock used as a real number cannot be run by DTRON's engine: clocks used as real numbers"
                + " (in arithmetic on doubles, or passed as a double) belong to statistical model checking, and the"
                + " engine treats clocks symbolically, as zones", refusal(n, "a clock used"));
    }

    @Test
    void aConditionalWithADoubleOrAClockInABranchIsADouble() throws ModelException {
        Network n = load(edge("clock x;\ndouble d;\nbool b;", "assign d = b ? 1.5 : 2, d = b ? x : 0;"));
        assertEquals("4:75: a clock used as a real number cannot be run by DTRON's engine: clocks used as real numbers"
                + " (in arithmetic on doubles, or passed as a double) belong to statistical model checking, and the"
                + " engine treats clocks symbolically, as zones", refusal(n, "a clock used"));
        assertEquals("4:58: cannot assign a double to 'i' of type int",
                error(edge("clock x;\nint i;\nbool b;", "assign i = b ? 1.5 : 2;")));
    }

    @Test
    void doublesAreInitialisedWithValuesComputableAtCompileTime() {
        assertEquals("2:18: the initial value of 'C' must be computable at compile time",
                error(edge("double v = 1.0;\nconst double C = v * 2;", "")));
        assertEquals("2:12: the initial value of 'd' must be computable at compile time",
                error(edge("clock x;\ndouble d = x;", "")));
    }

    @Test
    void clocksInIntegerArithmeticAreStillErrors() {
        assertEquals("3:58: '%' needs integers, not a clock (clocks can only be compared with integers, as in x < 5"
                + " or x - y <= 3, or reset, as in x = 0)", error(edge("clock x;\nint i;", "assign i = x % 2;")));
        assertEquals("3:62: argument 1 of 'abs' must be int, not a clock",
                error(edge("clock x;\nint i;", "assign i = abs(x);")));
        assertEquals("3:58: cannot assign a clock to 'i' of type int",
                error(edge("clock x;\nint i;", "assign i = x;")));
        assertEquals("3:58: cannot assign a double to 'i' of type int",
                error(edge("clock x;\nint i;", "assign i = x * 2;")));
    }

    @Test
    void clocksSetToDoublesAndToOtherClocks() throws ModelException {
        Network n = load(edge("clock x, y;\ndouble d = 0.5;", "assign x = 1.5, y = d, x = y;"));
        assertEquals("3:54: a clock set to a real number or to another clock cannot be run by DTRON's engine: the"
                + " engine resets clocks to integers, as zones need", refusal(n, "a clock set"));
        assertEquals("3:54: a clock can only be reset with '=', as in x = 0",
                error(edge("clock x;\ndouble d;", "assign x += 1.5;")));
        assertEquals("3:58: a clock is set to a number or a clock, not to an array (int[2])",
                error(edge("clock x;\nint a[2];", "assign x = a;")));
    }

    @Test
    void aClockComparedWithADoubleIsAnUpperBoundOrAGuardAsInUppaal() throws ModelException {
        // x <= 2.5 may stand in an invariant; x >= 2.5 (a guard in Uppaal 5) may not
        Network n = load("""
                clock x;
                process P() { state A { x <= 2.5 }; init A; trans A -> A { guard x >= 1.5 && x != 0.5; }; }
                system P;
                """);
        assertEquals(1, n.processes().get(0).edges().size());
        ModelException e = assertThrows(ModelException.class, () -> load("""
                clock x;
                process P() { state A { x >= 2.5 }; init A; }
                system P;
                """));
        Diagnostic d = e.errors().get(0);
        assertEquals("2:25", d.line() + ":" + d.column(), d::format);
        assertTrue(d.message().startsWith("an invariant is a conjunction of bounds on clocks"), d::format);
    }

    // ================================================================ rates

    @Test
    void ratesGivenByClocksAndRealValuedExpressions() throws ModelException {
        Network n = load("""
                clock x, y;
                hybrid clock h;
                process P() { state A { x' == y && h' == 2 * y + 1 && y' == 0 && x <= 10 }; init A; }
                system P;
                """);
        assertEquals("3:25: a clock rate given by a clock or a real number cannot be run by DTRON's engine: rates"
                + " between clocks and real-valued rates belong to statistical model checking, and the engine's zones"
                + " let clocks run at rate 1", refusal(n, "a clock rate"));
        assertEquals("1:44: a rate is written x' == expression, with a clock x and a number, not a clock and an"
                + " array (int[2])", error("""
                clock x; int a[2]; process P() { state A { x' == a }; init A; } system P;
                """));
        assertEquals("1:32: a rate is written x' == expression, with a clock x and a number, not an integer and an"
                + " integer", error("int i; process P() { state A { i' == 1 }; init A; } system P;"));
        assertEquals("3:53: a clock rate (x' == e) can only stand in an invariant",
                error(edge("clock x, y;\nint i;", "guard x' == y;")));
    }

    // ================================================================ clock guards on urgent channels

    @Test
    void aClockGuardOnAnUrgentChannelLoadsWithAWarningAsInUppaal() throws ModelException {
        Network n = load(edge("clock x;\nurgent chan u;", "guard x > 1; sync u!;"));
        assertEquals("3:53: a clock guard on an edge that synchronises on an urgent channel cannot be run by DTRON's"
                + " engine: Uppaal allows it only in statistical model checking (its symbolic engine refuses it too),"
                + " and the engine cannot let time pass while an urgent edge waits for its clock guard",
                refusal(n, "a clock guard"));
        assertTrue(n.warnings().stream().anyMatch(w -> w.line() == 3 && w.message().startsWith("a clock guard")),
                () -> n.warnings().toString());
        Network data = load(edge("clock x;\nint i;\nurgent chan u;", "guard i > 1; sync u!;"));
        assertTrue(data.startErrors().isEmpty(), "a guard on data is fine: " + data.startErrors());
    }

    // ================================================================ built-in constants

    @Test
    void theConstantsAndTypesUppaalDeclaresForEveryModel() throws ModelException {
        Network n = load(edge("""
                double d = M_PI + M_PI_2 + M_PI_4 + M_E + M_LOG2E + M_LOG10E + M_LN2 + M_LN10 + M_1_PI + M_2_PI
                    + M_2_SQRTPI + M_SQRT2 + M_SQRT1_2 + FLT_MIN + FLT_MAX + DBL_MIN + DBL_MAX;
                int8_t i8 = INT8_MAX; uint8_t u8 = UINT8_MAX; int16_t i16 = INT16_MIN; uint16_t u16 = UINT16_MAX;
                int32_t i32 = INT32_MIN; const int BIG = INT32_MAX; int small = INT8_MIN + INT16_MAX;""", ""));
        assertEquals(List.of(127, 255, -32768, 65535, Integer.MIN_VALUE, -128 + 32767),
                List.of("i8", "u8", "i16", "u16", "i32", "small").stream()
                        .map(v -> n.variable(v).orElseThrow().initial()[0]).toList());
        assertEquals("1:12: real numbers (double) cannot be run by DTRON's engine: the engine computes with integers"
                + " and clock zones", refusal(n, "real numbers").replace("1:1:", "1:12:"));
    }

    @Test
    void aModelMayDeclareTheBuiltInNamesItself() throws ModelException {
        // models written before Uppaal 5 declared these themselves
        Network n = load(edge("const int INT16_MAX = 100;\ntypedef int[0,3] int8_t;\nint8_t v = 3;\n"
                + "int w = INT16_MAX;", ""));
        assertEquals(100, n.variable("w").orElseThrow().initial()[0]);
        assertEquals("3:12: the initial value 4 of 'v' is outside its range int[0,3]",
                error(edge("typedef int[0,3] int8_t;\nint8_t u = 3;\nint8_t v = 4;", "")));
    }

    @Test
    void theBuiltInConstantsAreConstants() {
        assertEquals("2:54: cannot assign to 'M_PI': 'M_PI' is a constant",
                error(edge("", "assign M_PI = 3.0;")));
        assertEquals("1:9: 'i' is int and cannot be initialised with a double", error(edge("int i = M_E;", "")));
    }

    // ================================================================ == on arrays and structs

    @Test
    void arraysAndStructsOfTheSameTypeAreComparedWithEqualsAndNotEquals() throws ModelException {
        Network n = load(edge("int a[3], b[3];\nstruct { int p; bool q; } s, t;\nbool same = true;",
                "guard a == b || s != t; assign same = (a != b);"));
        assertEquals("4:53: '==' and '!=' on arrays and structs cannot be run by DTRON's engine: the engine compares"
                + " single values; compare the elements one by one", refusal(n, "'=='"));
        assertEquals("3:61: '==' compares arrays and structs of the same type (the same size, element type and"
                + " ranges), not an array (int[3]) and an array (int[2])",
                error(edge("int a[3], b[2];\nbool same;", "assign same = a == b;")));
        assertEquals("3:61: '<' cannot compare an array (int[3]) with an array (int[3])",
                error(edge("int a[3], b[3];\nbool less;", "assign less = a < b;")));
    }

    // ================================================================ external functions

    @Test
    void externalFunctionsWithAliasesStringsAndArraysOfClocks() throws ModelException {
        Network n = load(edge("""
                clock xs[2];
                double out[2];
                int a[3];
                import "/opt/lib/libcontrol.so" {
                    is_safe = bool is_the_world_safe();
                    void sample(clock& c[2], double& o[2]);
                    void log(const string& s);
                    double f(int v[3]);
                };""", "guard is_safe(); assign sample(xs, out), log(\"tick\"), out[0] = f(a);"));
        assertEquals("10:53: the external function 'is_safe' of \"/opt/lib/libcontrol.so\" cannot be run by DTRON's"
                + " engine: the engine does not load native libraries", refusal(n, "the external"));
    }

    @Test
    void callsOfExternalFunctionsAreTypeChecked() {
        String lib = "import \"lib.so\" { int count(int n); void log(const string& s); alias = int g(); };\nint i;";
        assertEquals("3:58: 'count' takes 1 argument, not 2", error(edge(lib, "assign i = count(1, 2);")));
        assertEquals("3:64: argument 1 of 'count' must be int, not a double", error(edge(lib, "assign i = count(1.5);")));
        assertEquals("3:58: argument 1 of 'log' must be string, not an integer", error(edge(lib, "assign log(3);")));
        assertEquals("3:58: cannot assign a string to 'i' of type int", error(edge(lib, "assign i = \"x\";")));
        assertEquals("3:58: unknown function 'g'", error(edge(lib, "assign i = g();")));
    }
}
