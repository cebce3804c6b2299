package io.dtron.engine.internal.eval;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.Expression;
import org.junit.jupiter.api.Test;

/** Data expressions: C arithmetic, short-circuit logic, arrays, structs, quantifiers, assignments and errors. */
class DataEvaluationTest {

    private static final String NUMBERS = "int a = -7; int b = 2; int z = 0;"
            + " int[-2147483647-1,2147483647] big = 2147483647, small = -2147483647-1;";

    private static int number(String expression) {
        return TestModel.value(NUMBERS, expression);
    }

    private static ModelRuntimeException numberError(String expression) {
        TestModel m = TestModel.guards(NUMBERS, expression);
        return assertThrows(ModelRuntimeException.class, () -> m.guard(0));
    }

    @Test
    void divisionAndRemainderTruncateTowardZero() {
        assertEquals(-3, number("a / b"));
        assertEquals(-1, number("a % b"));
        assertEquals(3, number("-a / b"));
        assertEquals(1, number("-a % b"));
        assertEquals(-1, number("a % -b"));
        assertEquals(3, number("a / -b"));
    }

    @Test
    void shiftsMinMaxAndBitOperators() {
        assertEquals(-28, number("a << 2"));
        assertEquals(-4, number("a >> 1"));
        assertEquals(-7, number("a <? b"));
        assertEquals(2, number("a >? b"));
        assertEquals(0, number("a & 6"));
        assertEquals(-5, number("a | b"));
        assertEquals(-5, number("a ^ b"));
        assertEquals(1, number("b ^ 3"));
        assertEquals(-1, number("a + b * 3"));
        assertEquals(7, number("-a"));
    }

    @Test
    void powerIsRightAssociativeAndChecked() {
        assertEquals(49, number("a ** b"));
        assertEquals(-343, number("a ** 3"));
        assertEquals(1, number("a ** z"));
        assertEquals(16, number("b ** b ** b"));
        assertEquals(1, number("(0 - 1) ** 2147483647 * -1"));
        assertEquals("integer overflow in 'b ** 31'", numberError("b ** 31").getMessage());
        assertEquals("negative exponent in 'b ** -b'", numberError("b ** -b").getMessage());
    }

    @Test
    void comparisonsAndLogicGiveZeroOrOne() {
        assertEquals(1, number("a < b"));
        assertEquals(0, number("a >= b"));
        assertEquals(1, number("a <= -7 && b > 1"));
        assertEquals(1, number("a != b"));
        assertEquals(0, number("a == b"));
        assertEquals(1, number("!(a == b)"));
        assertEquals(1, number("z || b"));
        assertEquals(0, number("b imply z"));
        assertEquals(1, number("z imply a / z"));
        assertEquals(5, number("a < b ? 5 : 6"));
        assertEquals(6, number("z ? 5 : 6"));
    }

    @Test
    void logicShortCircuits() {
        assertEquals(0, number("z != 0 && a / z > 0"));
        assertEquals(1, number("z == 0 || a / z > 0"));
        assertEquals(1, number("z != 0 imply a / z > 0"));
        assertEquals(10, number("z == 0 ? 10 : a / z"));
        assertEquals(3, number("z != 0 ? a / z : 3"));
    }

    @Test
    void arithmeticErrorsAreModelErrors() {
        ModelRuntimeException e = numberError("a / z");
        assertEquals("division by zero in 'a / z'", e.getMessage());
        assertEquals(5, e.pos().line());
        assertEquals("a / z", e.pos().text());
        assertEquals("division by zero in 'a % z'", numberError("a % z").getMessage());
        assertEquals("integer overflow in 'big + 1'", numberError("big + 1").getMessage());
        assertEquals("integer overflow in 'small - 1'", numberError("small - 1").getMessage());
        assertEquals("integer overflow in 'big * b'", numberError("big * b").getMessage());
        assertEquals("integer overflow in '-small'", numberError("-small").getMessage());
        assertEquals("integer overflow in 'small / -1'", numberError("small / -1").getMessage());
        assertEquals("integer overflow in 'big << b'", numberError("big << b").getMessage());
        assertTrue(numberError("a / z").format().startsWith("t.xta:"), numberError("a / z").format());
    }

    @Test
    void foldedModelErrorsFailOnlyWhenEvaluated() {
        TestModel m = TestModel.guards("int a[4]; int z = 0;", "z == 0 || a[5] == 1", "z != 0 || a[5] == 1",
                "z == 0 || 1 / 0 > 0", "z != 0 || 1 / 0 > 0");
        Expression.Binary or = (Expression.Binary) m.edge(1).guard();
        // a variable indexed out of range stays an index, checked when evaluated (it may be assigned, as in Uppaal)
        assertTrue(((Expression.Binary) or.right()).left() instanceof Expression.Index);
        assertEquals(1, m.guard(0));
        assertEquals("index 5 is out of range [0,3] of 'a'",
                assertThrows(ModelRuntimeException.class, () -> m.guard(1)).getMessage());
        assertEquals(1, m.guard(2));
        assertEquals("division by zero", assertThrows(ModelRuntimeException.class, () -> m.guard(3)).getMessage());
    }

    @Test
    void arraysWithAnIntegerRangeIndexStartAtItsLowerBound() {
        TestModel m = TestModel.of("typedef int[3,6] r_t; int a[r_t] = {30, 40, 50, 60}; int i = 4;",
                "guard a[i] == 40 && a[3] == 30 && a[6] == 60;", "assign a[i + 1] = 7, i = 6;",
                "guard a[i + 1] > 0;", "assign a[i - 4] = 1;");
        assertEquals(1, m.guard(0));
        m.run(1);
        assertArrayEquals(new int[] {30, 40, 7, 60}, m.slots("a"));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.guard(2));
        assertEquals("index 7 is out of range [3,6] of 'a'", e.getMessage());
        assertEquals("a[i + 1]", e.pos().text());
        e = assertThrows(ModelRuntimeException.class, () -> m.run(3));
        assertEquals("index 2 is out of range [3,6] of 'a'", e.getMessage());
    }

    @Test
    void twoDimensionalArraysAreRowMajor() {
        TestModel m = TestModel.of("int g[2][3] = {{1, 2, 3}, {4, 5, 6}}; int i = 1, j = 2;",
                "guard g[i][j] + g[0][j] * 10;", "assign g[i][j - 1] = g[i - 1][j] + 100, g[0][0]++;",
                "guard g[i][j + 1];", "assign g[0] = g[i];");
        assertEquals(36, m.guard(0));
        m.run(1);
        assertArrayEquals(new int[] {2, 2, 3, 4, 103, 6}, m.slots("g"));
        m.run(3);
        assertArrayEquals(new int[] {4, 103, 6, 4, 103, 6}, m.slots("g"));
        assertEquals("index 3 is out of range [0,2] of 'g[i]'",
                assertThrows(ModelRuntimeException.class, () -> m.guard(2)).getMessage());
    }

    @Test
    void scalarIndexedArraysAreZeroBased() {
        TestModel m = TestModel.of("typedef scalar[3] S; int[0,9] count[S]; bool seen[S];",
                "select s : S; assign count[s] += 2, seen[s] = true;",
                "select s : S; guard exists (t : S) seen[t] && t == s;");
        m.run(0, 1).run(0, 2).run(0, 2);
        assertArrayEquals(new int[] {0, 2, 4}, m.slots("count"));
        assertArrayEquals(new int[] {0, 1, 1}, m.slots("seen"));
        assertEquals(0, m.guard(1, 0));
        assertEquals(1, m.guard(1, 2));
    }

    @Test
    void structFieldsAndArraysOfStructs() {
        TestModel m = TestModel.of("typedef struct { int[0,5] a; bool b; int c[2]; } rec_t;"
                        + " rec_t r = {1, true, {7, 8}}; rec_t rs[2]; int k = 1;",
                "guard r.a + r.c[k] * 10 + r.b * 100;",
                "assign rs[k].c[0] = r.c[1], rs[k].a = r.a + 3, rs[0] = r, rs[0].b = false;",
                "assign rs[k].a = 6;");
        assertEquals(181, m.guard(0));
        m.run(1);
        assertArrayEquals(new int[] {1, 0, 7, 8, 4, 0, 8, 0}, m.slots("rs"));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.run(2));
        assertEquals("the value 6 is outside int[0,5] of 'rs[1].a'", e.getMessage());
        assertEquals(4, m.slots("rs")[4]);
    }

    @Test
    void constantTablesCanBeIndexedAtRunTime() {
        TestModel m = TestModel.guards("const int T[2][3] = {{1, 2, 3}, {4, 5, 6}};"
                        + " typedef struct { int x; int y; } p_t; const p_t PS[2] = {{1, 2}, {3, 4}}; int i = 1;",
                "T[i][i + 1] * 10 + T[i - 1][2]", "PS[i].y * 10 + PS[0].x", "T[i][i + 2]");
        assertEquals(63, m.guard(0));
        assertEquals(41, m.guard(1));
        assertEquals("index 3 is out of range [0,2] of 'T[i]'",
                assertThrows(ModelRuntimeException.class, () -> m.guard(2)).getMessage());
    }

    @Test
    void quantifiersBindTheirNameInTheFrame() {
        TestModel m = TestModel.of("int a[5] = {3, 1, 4, 1, 5}; int z = 0;",
                "guard forall (i : int[0,4]) a[i] > 0;",
                "guard exists (i : int[0,4]) a[i] == 4 && forall (j : int[0,2]) a[j] <= 4;",
                "guard sum (i : int[0,4]) a[i] * i;",
                "select k : int[0,4]; guard exists (i : int[0,4]) a[i] > a[k];",
                "guard forall (i : int[0,4]) a[i] != 1;",
                "guard exists (i : int[0,4]) a[i] == 9;",
                "guard forall (i : int[0,4]) a[i] > 0 && 10 / (i - z) > 0;");
        assertEquals(1, m.guard(0));
        assertEquals(1, m.guard(1));
        assertEquals(1 + 8 + 3 + 20, m.guard(2));
        assertEquals(1, m.guard(3, 3));
        assertEquals(0, m.guard(3, 4));
        assertEquals(0, m.guard(4));
        assertEquals(0, m.guard(5));
        assertEquals("division by zero in '10 / (i - z)'",
                assertThrows(ModelRuntimeException.class, () -> m.guard(6)).getMessage());
    }

    @Test
    void assignmentsCheckTheTargetRange() {
        TestModel m = TestModel.of("int[0,10] len = 9; int x; bool f; int[-3,3] r = -3;",
                "assign len++, x = len * 2, f = 5, r -= 0;",
                "assign len++;",
                "assign x = 40000;",
                "assign r--;",
                "assign f = 0, x = (len = 3) + 1;");
        m.run(0);
        assertEquals(10, m.get("len"));
        assertEquals(20, m.get("x"));
        assertEquals(1, m.get("f"));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.run(1));
        assertEquals("the value 11 is outside int[0,10] of 'len'", e.getMessage());
        assertEquals("len++", e.pos().text());
        assertEquals(10, m.get("len"));
        assertEquals("the value 40000 is outside int[-32768,32767] of 'x'",
                assertThrows(ModelRuntimeException.class, () -> m.run(2)).getMessage());
        assertEquals("the value -4 is outside int[-3,3] of 'r'",
                assertThrows(ModelRuntimeException.class, () -> m.run(3)).getMessage());
        m.run(4);
        assertEquals(0, m.get("f"));
        assertEquals(3, m.get("len"));
        assertEquals(4, m.get("x"));
    }

    @Test
    void incrementsAndCompoundAssignmentsHaveCValues() {
        TestModel m = TestModel.of("int x = 5, y, w = 20;",
                "assign y = x++ * 10;", "assign y = ++x * 10;", "assign y = x-- + --x;",
                "assign w /= 3, w %= 4, w <<= 3, w >>= 1, w |= 1, w &= 13, w ^= 2, w *= -1, w -= 1, w += 100;");
        m.run(0);
        assertEquals(6, m.get("x"));
        assertEquals(50, m.get("y"));
        m.run(1);
        assertEquals(70, m.get("y"));
        m.run(2);
        assertEquals(5, m.get("x"));
        assertEquals(7 + 5, m.get("y"));
        m.run(3);
        // 20/3=6, 6%4=2, 2<<3=16, 16>>1=8, 8|1=9, 9&13=9, 9^2=11, -11, -12, 88
        assertEquals(88, m.get("w"));
    }

    @Test
    void templateLocalsAreNamedWithTheirProcess() {
        TestModel m = TestModel.load("""
                process Gate() {
                    int[0,2] len = 2;
                    int list[3];
                    state A; init A;
                    trans A -> A { assign len++; }, A -> A { assign list[len] = 40000; };
                }
                system Gate;
                """);
        assertEquals("the value 3 is outside int[0,2] of 'Gate.len'",
                assertThrows(ModelRuntimeException.class, () -> m.run(0)).getMessage());
        assertEquals("the value 40000 is outside int[-32768,32767] of 'Gate.list[2]'",
                assertThrows(ModelRuntimeException.class, () -> m.run(1)).getMessage());
    }

    @Test
    void aStateVectorOfTheWrongSizeIsRefused() {
        TestModel m = TestModel.guards("int x;", "x == 0");
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> m.evaluator.evaluate(m.edge(0).guard(), new int[3], null));
        assertTrue(e.getMessage().contains("3 slots"), e.getMessage());
    }
}
