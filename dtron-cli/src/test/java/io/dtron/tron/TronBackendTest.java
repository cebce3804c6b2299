package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.troninstaller.TronInstallation;
import io.dtron.troninstaller.TronLauncher;
import io.dtron.troninstaller.TronNotFoundException;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.stream.Collectors;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The TRON backend against a stand-in for TRON: a {@code tron} script in {@code TRON_HOME/bin} that runs DTRON in
 * TRON's place ({@link FakeTronMain}), so that the launcher, the adapter side of the protocol, the bridge and the
 * reading of the verdict and seed are all exercised without TRON itself.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronBackendTest {
    private static Path model;
    private static Network lightContr;
    private static TestInterface lampInterface;

    @TempDir
    Path dir;

    @BeforeAll
    static void load() throws Exception {
        Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        model = tron.resolve("LightContr.xml").toAbsolutePath();
        lightContr = ModelLoader.load(model);
        lampInterface = TestInterface.fromFile(lightContr, tron.resolve("LightContr.trn"));
    }

    private TronInstallation fakeInstallation(String body) throws IOException {
        Path bin = dir.resolve("tron-home").resolve("bin");
        Files.createDirectories(bin);
        Path script = bin.resolve("tron");
        Files.writeString(script, "#!/bin/sh\n" + body + "\n");
        Files.setPosixFilePermissions(script, PosixFilePermissions.fromString("rwxr-xr-x"));
        return new TronInstallation(Map.of("TRON_HOME", dir.resolve("tron-home").toString()), "Linux");
    }

    private TronInstallation dtronAsTron() throws IOException {
        String command = ChildProcess.command(FakeTronMain.class).stream().map(a -> "'" + a + "'")
                .collect(Collectors.joining(" "));
        return fakeInstallation("exec " + command + " \"$@\"");
    }

    private TestOptions options(long seed) {
        return new TestOptions(seed, TronLampEndToEndTest.REAL_TIME_UNIT, 300, DelayPolicy.RANDOM, 0, false);
    }

    @Test
    void theCorrectLampPassesWithTronAsTheBackend() throws Exception {
        TronBackend backend = TronBackend.installed(dtronAsTron(), null);
        TestResult result = backend.run(model, lampInterface, new LampAdapter(false), options(42));
        assertEquals(Verdict.PASSED, result.verdict(), result.explanation());
        assertEquals(42, result.seed());
        assertTrue(result.explanation().startsWith("the timeout of 300 time units was reached"), result.explanation());
        assertTrue(result.inputs() > 0 && result.outputs() > 0, result.statisticsLine());
    }

    @Test
    void theLateLampFailsWithTronAsTheBackend() throws Exception {
        TronBackend backend = TronBackend.installed(dtronAsTron(), null);
        TestResult result = backend.run(model, lampInterface, new LampAdapter(true), options(43));
        assertEquals(Verdict.FAILED, result.verdict(), result.explanation());
        assertTrue(result.explanation().contains("level"), result.explanation());
    }

    @Test
    void aTronThatEndsWithoutConnectingIsAClearError() throws Exception {
        TronBackend backend = TronBackend.installed(fakeInstallation("echo 'tron: cannot parse the model' >&2\n"
                + "exit 1"), null);
        IOException e = assertThrows(IOException.class, () -> backend.run(model, lampInterface,
                new LampAdapter(false), options(1)));
        assertTrue(e.getMessage().contains("TRON ended (exit code 1) without connecting to DTRON; it printed: tron:"
                + " cannot parse the model"), e.getMessage());
    }

    @Test
    void virtualTimeAndAMissingTronAreRefusedClearly() throws Exception {
        TronBackend backend = new TronBackend(new TronLauncher(dir.resolve("tron")), null);
        IllegalArgumentException virtual = assertThrows(IllegalArgumentException.class, () -> backend.run(model,
                lampInterface, new LampAdapter(false), options(1).withVirtualTime(true)));
        assertTrue(virtual.getMessage().contains("real time only"), virtual.getMessage());
        TronNotFoundException missing = assertThrows(TronNotFoundException.class, () -> TronBackend.installed(
                new TronInstallation(Map.of("PATH", dir.toString()), "Linux"), null));
        assertTrue(missing.getMessage().contains("licence forbids redistribution"), missing.getMessage());
    }

    @Test
    void delayPoliciesBecomeTronsDelayOption() {
        assertEquals("random", TronBackend.delayArgument(options(1)));
        assertEquals("eager", TronBackend.delayArgument(options(1).withDelayPolicy(DelayPolicy.EAGER, 0)));
        assertEquals("lazy", TronBackend.delayArgument(options(1).withDelayPolicy(DelayPolicy.LAZY, 0)));
        assertEquals("0,200", TronBackend.delayArgument(options(1).withDelayPolicy(DelayPolicy.RANDOM_BOUNDED, 200)));
    }
}
