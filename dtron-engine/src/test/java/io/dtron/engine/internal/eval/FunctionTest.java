package io.dtron.engine.internal.eval;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

/** User functions: parameters by value and by reference, locals, control flow, recursion and runtime errors. */
class FunctionTest {

    @Test
    void valueParametersAreCopiesIncludingArraysAndStructs() {
        TestModel m = TestModel.of("""
                typedef struct { int a; int b; } p_t;
                int arr[3] = {1, 2, 3};
                p_t p = {10, 20};
                int r;
                int total(int v[3]) { v[0] = 100; return v[0] + v[1] + v[2]; }
                int swapSum(p_t q) { int t = q.a; q.a = q.b; q.b = t; return q.a * 1000 + q.b; }
                int twice(int x) { x = x * 2; return x; }
                """, "assign r = total(arr);", "assign r = swapSum(p);", "assign r = twice(arr[2]);");
        m.run(0);
        assertEquals(105, m.get("r"));
        assertArrayEquals(new int[] {1, 2, 3}, m.slots("arr"));
        m.run(1);
        assertEquals(20010, m.get("r"));
        assertArrayEquals(new int[] {10, 20}, m.slots("p"));
        m.run(2);
        assertEquals(6, m.get("r"));
        assertEquals(3, m.slots("arr")[2]);
    }

    @Test
    void referenceParametersReachVariablesElementsFieldsAndWholeArrays() {
        TestModel m = TestModel.of("""
                typedef struct { int a; int b; } p_t;
                int x = 1;
                int arr[3] = {1, 2, 3};
                p_t p = {10, 20};
                int i = 2;
                void inc(int &v) { v++; }
                void fill(int &v[3], int k) { for (j : int[0,2]) v[j] = k + j; }
                void both(int &v[3], int &w) { v[1] = w; w = 0; }
                """, "assign inc(x), inc(arr[i]), inc(p.b);", "assign fill(arr, 7);", "assign both(arr, arr[2]);");
        m.run(0);
        assertEquals(2, m.get("x"));
        assertArrayEquals(new int[] {1, 2, 4}, m.slots("arr"));
        assertArrayEquals(new int[] {10, 21}, m.slots("p"));
        m.run(1);
        assertArrayEquals(new int[] {7, 8, 9}, m.slots("arr"));
        m.run(2);
        assertArrayEquals(new int[] {7, 9, 0}, m.slots("arr"));
    }

    @Test
    void aReferenceToTheCallersLocalStaysValidAcrossNestedCalls() {
        TestModel m = TestModel.of("""
                typedef int[-2147483647-1,2147483647] big;
                big r;
                void inc(big &v) { v++; }
                void incInt(int &v) { v++; }
                void addTwice(big &v, int &w[2]) { inc(v); incInt(w[1]); inc(v); }
                big deep(int n) { int here[2]; big k = 10; here[1] = n; if (n > 0) { k = deep(n - 1); }
                                  addTwice(k, here); return k * 100 + here[1]; }
                int local() { big k = 5; int w[2]; addTwice(k, w); incInt(w[0]); return k * 10 + w[0] + w[1]; }
                """, "assign r = local();", "assign r = deep(2);");
        m.run(0);
        assertEquals(72, m.get("r"));
        m.run(1);
        // deep(0) = 12 * 100 + 1; deep(1) = (1201 + 2) * 100 + 2; deep(2) = (120302 + 2) * 100 + 3
        assertEquals(12030403, m.get("r"));
    }

    @Test
    void recursion() {
        TestModel m = TestModel.guards("""
                typedef int[-2147483647-1,2147483647] big;
                int n = 10;
                big fact(int k) { if (k <= 1) return 1; return k * fact(k - 1); }
                int fib(int k) { return k < 2 ? k : fib(k - 1) + fib(k - 2); }
                int gcd(int a, int b) { return b == 0 ? a : gcd(b, a % b); }
                """, "fact(n)", "fib(n + 5)", "gcd(n * 84, 36)", "fact(n + 3)");
        assertEquals(3628800, m.guard(0));
        assertEquals(610, m.guard(1));
        assertEquals(12, m.guard(2));
        assertEquals("integer overflow in 'k * fact(k - 1)'",
                assertThrows(ModelRuntimeException.class, () -> m.guard(3)).getMessage());
    }

    @Test
    void loopsWithBreakAndContinue() {
        TestModel m = TestModel.guards("""
                int limit = 20;
                int sumOdd() { int s = 0, i; for (i = 0; i < limit; i++) { if (i % 2 == 0) continue; if (i > 9) break;
                               s += i; } return s; }
                int whileLoop() { int i = 0, s = 0; while (true) { i++; if (i == 3) continue; if (i > 5) break;
                                  s = s * 10 + i; } return s; }
                int doLoop() { int i = 0; do { i += 4; if (i == 8) continue; } while (i < limit); return i; }
                int iterate() { int s = 0; for (k : int[2,6]) { if (k == 3) continue; if (k == 6) break; s += k; }
                                return s; }
                int nested() { int s = 0; for (i : int[0,3]) { for (j : int[0,3]) { if (j > i) break; s++; } }
                               return s; }
                int early() { for (i : int[0,9]) { while (true) { if (i == 4) return i * 100; break; } } return -1; }
                int forever() { int i = 0; while (true) { i = 1 - i; } return i; }
                int forEver() { for (;;) { } return 0; }
                """, "sumOdd()", "whileLoop()", "doLoop()", "iterate()", "nested()", "early()", "forever()",
                "forEver()");
        assertEquals(1 + 3 + 5 + 7 + 9, m.guard(0));
        assertEquals(1245, m.guard(1));
        assertEquals(20, m.guard(2));
        assertEquals(2 + 4 + 5, m.guard(3));
        assertEquals(1 + 2 + 3 + 4, m.guard(4));
        assertEquals(400, m.guard(5));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.guard(6));
        assertTrue(e.getMessage().contains("more than 10000000 loop iterations"), e.getMessage());
        assertTrue(e.pos().text().startsWith("while"), e.pos().text());
        assertTrue(assertThrows(ModelRuntimeException.class, () -> m.guard(7)).getMessage()
                .contains("endless loop"));
    }

    @Test
    void localsAreInitialisedFromExpressionsTablesAndArrays() {
        TestModel m = TestModel.guards("""
                const int T[3] = {4, 5, 6};
                int g[3] = {7, 8, 9};
                int i = 1;
                int fromTable() { int t[3] = T; int u[3] = {1, 2, 3}; return t[i] * 10 + u[i]; }
                int fromArray() { int t[3] = g; t[0] = 0; return t[0] + t[1] + t[2] + g[0]; }
                int defaults() { int a; int[2,5] b; int[-5,-2] c; bool d; int e[2];
                                 return a + b * 10 + c * 100 + d + e[1]; }
                int range() { int[0,3] k = i + 5; return k; }
                """, "fromTable()", "fromArray()", "defaults()", "range()");
        assertEquals(52, m.guard(0));
        assertEquals(24, m.guard(1));
        assertEquals(20 - 200, m.guard(2));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.guard(3));
        assertEquals("the value 6 is outside int[0,3] of 'k'", e.getMessage());
    }

    @Test
    void structsCanBeReturned() {
        TestModel m = TestModel.of("""
                typedef struct { int a; int b[2]; } s_t;
                s_t s;
                s_t make(int x) { s_t r; r.a = x; r.b[1] = x * 2; return r; }
                s_t twice(int x) { return make(make(x).b[1]); }
                int total(s_t v) { return v.a + v.b[0] + v.b[1]; }
                """, "assign s = twice(3);", "assign s.a = total(make(5));");
        m.run(0);
        assertArrayEquals(new int[] {6, 0, 12}, m.slots("s"));
        m.run(1);
        assertEquals(15, m.get("s"));
    }

    @Test
    void parametersAndReturnValuesAreCheckedAgainstTheirTypes() {
        TestModel m = TestModel.guards("""
                int x = 7;
                int[0,5] clip(int[0,5] v) { return v; }
                int[0,5] wide(int v) { return v; }
                bool flag(bool b) { return b; }
                """, "clip(x)", "wide(x)", "flag(x)", "clip(x - 3)");
        assertEquals("the value 7 is outside int[0,5] of parameter 'v'",
                assertThrows(ModelRuntimeException.class, () -> m.guard(0)).getMessage());
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.guard(1));
        assertEquals("the value 7 is outside int[0,5] of the return value of 'wide'", e.getMessage());
        assertEquals("v", e.pos().text());
        assertEquals(1, m.guard(2));
        assertEquals(4, m.guard(3));
    }

    @Test
    void functionsThatEndWithoutAValueAndFailedAssertionsAreModelErrors() {
        TestModel m = TestModel.guards("""
                int x = 3;
                int maybe(int v) { if (v > 0) return v; }
                int checked(int v) { assert(v < 3); return v; }
                """, "maybe(x)", "maybe(x - 3)", "checked(x - 1)", "checked(x)");
        assertEquals(3, m.guard(0));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.guard(1));
        assertEquals("function 'maybe' ended without returning a value", e.getMessage());
        assertEquals(2, e.pos().line());
        assertEquals(2, m.guard(2));
        e = assertThrows(ModelRuntimeException.class, () -> m.guard(3));
        assertEquals("the assertion 'v < 3' failed", e.getMessage());
    }

    @Test
    void endlessRecursionIsStoppedWithAClearError() {
        TestModel m = TestModel.guards("int down(int v) { return down(v + 1); }"
                + " int ok(int v) { return v <= 0 ? 0 : 1 + ok(v - 1); }", "down(0)", "ok(900)");
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.guard(0));
        assertEquals("the calls nest 1001 deep (in 'down'), too deep to go on; is there an endless recursion?",
                e.getMessage());
        assertEquals(900, m.guard(1));
    }

    @Test
    void aLongChainOfFunctionsCompilesWithoutRecursionAndRunsToTheLimitOfCalls() throws InterruptedException {
        // f1 calls f0, f2 calls f1, ...: compiling each callee inside its caller overflowed the stack at about a
        // thousand functions, with no place named
        StringBuilder functions = new StringBuilder("int f0() { return 1; }\n");
        for (int i = 1; i < 3000; i++) {
            functions.append("int f").append(i).append("() { return f").append(i - 1).append("() + 1; }\n");
        }
        TestModel m = TestModel.guards(functions.toString(), "f900()", "f2999()");
        Throwable[] thrown = new Throwable[2];
        Thread small = new Thread(null, () -> {
            try {
                thrown[0] = new AssertionError(m.guard(0));
                m.guard(1);
            } catch (Throwable t) {
                thrown[1] = t;
            }
        }, "small stack", 1 << 20);
        small.start();
        small.join();
        assertEquals("901", String.valueOf(thrown[0] == null ? thrown[1] : thrown[0].getMessage()),
                "a chain of 900 calls runs");
        assertTrue(thrown[1] instanceof ModelRuntimeException, String.valueOf(thrown[1]));
        assertTrue(thrown[1].getMessage().matches("the calls nest \\d+ deep \\(in 'f\\d+'\\), too deep to go on; .*"),
                thrown[1].getMessage());
    }

    @Test
    void aRecursionDeeperThanTheJavaStackIsAModelErrorToo() throws InterruptedException {
        TestModel m = TestModel.guards("""
                int n = 999;
                int f(int k) { if (k > 0) { while (true) { for (i : int[0,1]) { if (i == 0) {
                    return 1 + (k > 0 ? f(k - 1) : 0); } } } } return 0; }
                """, "f(n)", "f(3)");
        Throwable[] thrown = new Throwable[1];
        Thread small = new Thread(null, () -> {
            try {
                m.guard(0);
            } catch (Throwable t) {
                thrown[0] = t;
            }
        }, "small stack", 128 << 10);
        small.start();
        small.join();
        assertTrue(thrown[0] instanceof ModelRuntimeException, String.valueOf(thrown[0]));
        assertTrue(thrown[0].getMessage().matches("the calls nest \\d+ deep \\(in 'f'\\), too deep to go on; .*"),
                thrown[0].getMessage());
        assertEquals(3, m.guard(1));
    }

    @Test
    void functionsOfTemplatesChangeTheirProcessVariables() {
        TestModel m = TestModel.load("""
                process P(const int k) {
                    int v;
                    void set() { v = k * 10; }
                    state A; init A;
                    trans A -> A { assign set(); };
                }
                P1 = P(1);
                P2 = P(2);
                system P1, P2;
                """);
        m.run(m.process("P2").edges().get(0));
        assertEquals(0, m.get("P1.v"));
        assertEquals(20, m.get("P2.v"));
        m.run(m.process("P1").edges().get(0));
        assertEquals(10, m.get("P1.v"));
    }
}
