package io.dtron.engine.internal.tester;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import org.junit.jupiter.api.Test;

/**
 * Models that load but that the engine cannot run: the run is refused with one message that names the
 * feature, its place and why, before anything is evaluated.
 */
class UnsupportedModelTest {

    private static String refusal(String model) throws Exception {
        Network network = ModelLoader.load("m.xta", model);
        return assertThrows(UnsupportedModelException.class, () -> new Semantics(network, 1000)).getMessage();
    }

    @Test
    void aBranchpointIsRefusedWithItsPlace() throws Exception {
        assertEquals("the model cannot start: m.xta:5:18: error: a branchpoint cannot be run by DTRON's engine: it is a"
                + " probabilistic choice of statistical model checking, and the engine has no probabilities (template P)",
                refusal("""
                        process P() {
                        state A, B;
                        branchpoint C;
                        init A;
                        trans A -> C {}, C -> A {}, C -> B {};
                        }
                        system P;
                        """));
    }

    @Test
    void aBuiltInFunctionOfStatisticalModelCheckingIsRefused() throws Exception {
        assertEquals("the model cannot start: m.xta:2:58: error: the built-in function 'fint' cannot be run by"
                + " DTRON's engine: the engine evaluates the integer functions of the model, not the real-valued and"
                + " random functions of statistical model checking (template P, assignment label)",
                refusal("""
                        int i;
                        process P() { state A; init A; trans A -> A { assign i = fint(3); }; }
                        system P;
                        """));
    }

    @Test
    void aSpawnIsRefused() throws Exception {
        assertEquals("the model cannot start: m.xta:3:54: error: dynamic templates (spawn, exit, numOf) cannot be run"
                + " by DTRON's engine: the engine runs the fixed set of processes of the system line (template P, assignment label)",
                refusal("""
                        dynamic W();
                        process W() { state A; init A; }
                        process P() { state A; init A; trans A -> A { assign spawn W(); }; }
                        system P;
                        """));
    }
}
