package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.SharedModels;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.stream.Collectors;
import java.util.stream.Stream;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

/**
 * Every model in {@code ../shared/models} either loads and type-checks, or is rejected with the precise error
 * that Uppaal itself gives it.
 *
 * <p>SOURCES.md names one invalid file, {@code decl-04.xta}. The test suite those files come from also records
 * the output of Uppaal's own type checker (utap) for each file, and utap rejects thirteen more of them; DTRON
 * follows Uppaal, so they are listed here with the error utap reported and the one DTRON gives. Only
 * {@code tmpl-binding-01.xta} differs from that record: utap rejected {@code tmpl-binding-02} and {@code -03}
 * ("must be computable at compile time" for a local initialised from a reference parameter) but not
 * {@code -01}, which does exactly the same; DTRON applies the rule to all three.
 */
class SharedModelsLoadTest {

    /** File name -> (line:column of the first error, a part of its message). */
    private static final Map<String, Expected> REJECTED = Map.ofEntries(
            Map.entry("decl-04.xta", new Expected(11, 36, "cannot assign to 'pid': 'pid' is a free parameter of Processes")),
            // utap: $Incompatible_argument (non-const free parameter passed to a value parameter)
            Map.entry("err-01.xta", new Expected(12, 32, "passed by value, so it must be computable at compile time")),
            // utap: $Incompatible_argument (chan where broadcast chan is expected)
            Map.entry("err-03.xta", new Expected(14, 32, "must be a broadcast chan, but 'a[pid]' is a chan")),
            // utap: $Incompatible_argument (array of channels by value)
            Map.entry("err-05.xta", new Expected(14, 32, "an array of channels must be passed by reference")),
            // utap: $Cannot_have_initialiser
            Map.entry("err-06.xta", new Expected(7, 14, "channel 'c' cannot have an initialiser")),
            // utap: $Incompatible_argument, $Must_be_computable_at_compile_time, $Channel_expected
            Map.entry("err-07.xta", new Expected(17, 32, "a clock parameter must be a reference")),
            // utap: $Must_be_computable_at_compile_time, $Channel_expected
            Map.entry("err-08.xta", new Expected(9, 21, "the initial value of clock 'cl' must be computable at compile time")),
            // utap: $Array_expected, $Incompatible_argument
            Map.entry("err-09.xta", new Expected(17, 32, "a clock parameter must be a reference")),
            // utap: $Free_process_parameters_must_be_a_bounded_integer_or_a_scalar
            Map.entry("err-11.xta", new Expected(6, 46, "free parameter 'b' of Processes must be a bounded integer")),
            // utap: $CSP_and_IO_synchronisations_cannot_be_mixed
            Map.entry("err-12.xta", new Expected(21, 21, "CSP synchronisations (sync a;) and send/receive")),
            // utap: $syntax_error: $unexpected '}' (an empty IO list)
            Map.entry("err-13.xta", new Expected(25, 7, "syntax error: unexpected '}'")),
            // see the class comment
            Map.entry("tmpl-binding-01.xta", new Expected(6, 11, "the initial value of 'k' must be computable")),
            // utap: $Must_be_computable_at_compile_time
            Map.entry("tmpl-binding-02.xta", new Expected(6, 11, "the initial value of 'k' must be computable")),
            Map.entry("tmpl-binding-03.xta", new Expected(8, 11, "the initial value of 'k' must be computable")),
            // utap: $Free_process_parameters_must_be_a_bounded_integer_or_a_scalar
            Map.entry("tmpl-partial-03.xta", new Expected(14, 14, "free parameter 'i' of Q3 must be a bounded integer")));

    private record Expected(int line, int column, String message) {
    }

    static Stream<Path> models() {
        return SharedModels.modelFiles().stream();
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("models")
    void loadsOrIsRejectedAsUppaalDoes(Path file) {
        String name = file.getFileName().toString();
        Expected expected = REJECTED.get(name);
        if (expected == null) {
            Network network = assertLoads(file);
            assertFalse(network.processes().isEmpty(), name + " has processes");
            return;
        }
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(file), name + " must be rejected");
        // errors come sorted by position: the one Uppaal names is among them, not always the first
        Diagnostic found = e.errors().stream().filter(d -> d.message().contains(expected.message())).findFirst()
                .orElseThrow(() -> new AssertionError(name + ": no error says \"" + expected.message() + "\":\n"
                        + e.getMessage()));
        assertEquals(expected.line(), found.line(), name + " line: " + found.format());
        assertEquals(expected.column(), found.column(), name + " column: " + found.format());
        assertTrue(found.format().startsWith(file.toString() + ":" + expected.line() + ":" + expected.column()
                + ": error: "), found.format());
        assertEquals(e.errors().stream().sorted(java.util.Comparator.comparingInt(Diagnostic::line)
                .thenComparingInt(Diagnostic::column)).toList(), e.errors(), name + ": errors sorted by position");
    }

    @Test
    void theRejectedFilesAllExist() {
        List<String> names = SharedModels.modelFiles().stream().map(p -> p.getFileName().toString()).toList();
        for (String rejected : REJECTED.keySet()) {
            assertTrue(names.contains(rejected), rejected);
        }
        assertTrue(names.size() - REJECTED.size() >= 70, "most shared models load: " + names.size());
    }

    @Test
    void decl04ReportsBothAssignmentsToTheFreeParameter() {
        ModelException e = assertThrows(ModelException.class,
                () -> ModelLoader.load(SharedModels.root().resolve("xta-syntax/decl-04.xta")));
        assertEquals(List.of("11:36", "12:36"),
                e.errors().stream().map(d -> d.line() + ":" + d.column()).toList());
    }

    @Test
    void fischerExpandsOneProcessPerIdentifier() {
        Network n = assertLoads(SharedModels.root().resolve("uppaal-examples/fischer.xml"));
        // typedef int[1,6] id_t; P(const id_t pid); system P;
        assertEquals(List.of("P(1)", "P(2)", "P(3)", "P(4)", "P(5)", "P(6)"), processNames(n));
        assertEquals(6, n.clockCount());
        assertEquals(4, n.processes().get(0).locations().size());
    }

    @Test
    void fischerWithSymmetryExpandsOverTheScalarSet() {
        Network n = assertLoads(SharedModels.root().resolve("uppaal-examples/fischer_symmetry.xml"));
        // const int N = 5; typedef scalar[N] pid_t; system P;
        assertEquals(5, n.processes().size());
        assertTrue(processNames(n).stream().allMatch(s -> s.startsWith("P(")), processNames(n).toString());
    }

    @Test
    void trainGateHasSixTrainsAndAGate() {
        for (String file : List.of("train-gate.xml", "train-gate-utap.xml")) {
            Network n = assertLoads(SharedModels.root().resolve("uppaal-examples/" + file));
            assertEquals(List.of("Train(0)", "Train(1)", "Train(2)", "Train(3)", "Train(4)", "Train(5)", "Gate"),
                    processNames(n), file);
            assertEquals(6, n.clockCount(), file);
            // chan appr[N], stop[N], leave[N]; urgent chan go[N];
            assertEquals(24, n.channelCount(), file);
            assertTrue(n.channel("go").orElseThrow().kind().urgent(), file);
            // Gate: id_t list[N+1]; int[0,N] len;
            assertEquals(7, n.variable("Gate.list").orElseThrow().size(), file);
            assertEquals(new Type.Int(0, 6), n.variable("Gate.len").orElseThrow().type(), file);
            assertEquals(4, n.functions().stream().filter(f -> "Gate".equals(f.owner())).count(), file);
        }
    }

    @Test
    void bridgeInstantiatesSoldiersWithTheirDelays() {
        Network n = assertLoads(SharedModels.root().resolve("uppaal-examples/bridge.xml"));
        assertEquals(5, n.processes().size());
        assertEquals(1, n.processes().stream().filter(p -> p.template().equals("Torch")).count());
        assertEquals(4, n.processes().stream().filter(p -> p.template().equals("Soldier")).count());
    }

    @Test
    void partialInstantiationWithAFreeParameterExpandsPerValue() {
        Network n = assertLoads(SharedModels.root().resolve("xta-syntax/tmpl-partial-05.xta"));
        // Q1 = Q(v, 0); Q2 = Q(u, 1); Q3(const int [0,1] i) = Q(u,i);
        assertEquals(List.of("Q1", "Q2", "Q3(0)", "Q3(1)"), processNames(n));
        assertTrue(n.startErrors().isEmpty());
    }

    @Test
    void anArgumentOutOfBoundsInOneExpandedProcessStopsTheRunButNotTheLoad() {
        Network n = assertLoads(SharedModels.root().resolve("xta-syntax/tmpl-partial-06.xta"));
        // Q3(const int [0,3] i) = Q(u,i) indexes data[2][3] with i = 2 and 3
        assertEquals(6, n.processes().size());
        assertEquals(2, n.startErrors().size());
        assertTrue(n.startErrors().get(0).message().contains("process Q3(2)"), n.startErrors().get(0).format());
    }

    @Test
    void oldUppaal3SyntaxLoads() {
        Network n = assertLoads(SharedModels.root().resolve("uppaal-examples/hddi_input_05.ta"));
        assertEquals(6, n.processes().size());
        assertEquals(10, n.channelCount());
    }

    @Test
    void lightControllerInterfaceComesFromItsTrnFile() throws ModelException {
        Path tron = SharedModels.root().resolve("tron");
        Network n = assertLoads(tron.resolve("LightContr.xml"));
        TestInterface i = TestInterface.fromFile(n, tron.resolve("LightContr.trn"));
        assertEquals(List.of("grasp", "release"), i.inputs().stream().map(TestInterface.ObservableChannel::name).toList());
        assertEquals(List.of("level"), i.outputs().stream().map(TestInterface.ObservableChannel::name).toList());
        assertEquals("adapLevel", i.outputs().get(0).variables().get(0).name());
        assertEquals(1000L, i.timeUnitMicros());
        assertEquals(1000L, i.timeout());
    }

    private static Network assertLoads(Path file) {
        try {
            Network network = ModelLoader.load(file);
            assertNotNull(network);
            return network;
        } catch (ModelException e) {
            throw new AssertionError(file + " must load:\n" + e.diagnostics().stream().map(Diagnostic::format)
                    .collect(Collectors.joining("\n")), e);
        }
    }

    private static List<String> processNames(Network n) {
        return n.processes().stream().map(Process::name).toList();
    }
}
