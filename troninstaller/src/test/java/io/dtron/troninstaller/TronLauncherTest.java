package io.dtron.troninstaller;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.charset.Charset;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.apache.commons.exec.CommandLine;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

@Timeout(value = 30, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronLauncherTest {
    @TempDir
    Path dir;

    private Path fakeTron(String body) throws IOException {
        Path file = dir.resolve("bin").resolve("tron");
        Files.createDirectories(file.getParent());
        Files.writeString(file, "#!/bin/sh\n" + body + "\n");
        Files.setPosixFilePermissions(file, PosixFilePermissions.fromString("rwxr-xr-x"));
        return file;
    }

    @Test
    void theCommandLineHasTronsOptionsTheModelAndTheAdaptersAddress() {
        Path model = Path.of("/models/Light Contr.xml");
        TronArguments args = new TronArguments(model, "127.0.0.1", 9999, "10,200", 300L, 42L, 1, List.of("-U", "5"));
        CommandLine command = new TronLauncher(Path.of("/opt/tron/bin/tron")).commandLine(args);
        assertEquals("/opt/tron/bin/tron", command.getExecutable());
        assertArrayEquals(new String[] {"-I", "SocketAdapter", "-v", "1", "-P", "10,200", "-F", "300", "-X", "42",
            "-U", "5", "/models/Light Contr.xml", "--", "127.0.0.1", "9999"}, command.getArguments());
    }

    @Test
    void optionsNotGivenAreLeftOut() {
        TronArguments args = new TronArguments(Path.of("m.xml"), "localhost", 1, null, null, null, null, List.of());
        assertEquals(List.of("-I", "SocketAdapter", "m.xml", "--", "localhost", "1"), args.toList());
        assertThrows(IllegalArgumentException.class, () -> new TronArguments(Path.of("m.xml"), "localhost", 0, null,
                null, null, null, List.of()));
    }

    @Test
    void aLaunchedTronsOutputAndExitCodeAreCollected() throws Exception {
        Path tron = fakeTron("echo \"args: $*\"\necho 'TEST FAILED: output too late' >&2\nexit 2");
        ByteArrayOutputStream echo = new ByteArrayOutputStream();
        TronArguments args = new TronArguments(dir.resolve("model.xml"), "127.0.0.1", 4000, "eager", 10L, 7L, null,
                List.of());
        try (RunningTron running = new TronLauncher(tron).start(args, echo, Duration.ofSeconds(20))) {
            assertEquals(2, running.waitFor(Duration.ofSeconds(20)));
            assertFalse(running.isRunning());
            String output = running.output();
            assertTrue(output.contains("args: -I SocketAdapter -P eager -F 10 -X 7 " + dir.resolve("model.xml")
                    + " -- 127.0.0.1 4000"), output);
            assertTrue(output.contains("TEST FAILED: output too late"), output);
            assertEquals(output, echo.toString(Charset.defaultCharset()));
        }
    }

    @Test
    void aTronThatRunsTooLongIsEnded() throws Exception {
        Path tron = fakeTron("sleep 30");
        TronArguments args = new TronArguments(dir.resolve("model.xml"), "127.0.0.1", 4000, null, null, null, null,
                List.of());
        try (RunningTron running = new TronLauncher(tron).start(args, null, Duration.ofSeconds(30))) {
            IOException e = assertThrows(IOException.class, () -> running.waitFor(Duration.ofMillis(300)));
            assertTrue(e.getMessage().contains("still ran after"), e.getMessage());
        }
    }

    @Test
    void launchingWithoutTronSaysWhatToDo() {
        TronInstallation none = new TronInstallation(Map.of("PATH", dir.toString()), "Linux");
        TronNotFoundException e = assertThrows(TronNotFoundException.class, () -> TronLauncher.installed(none));
        assertTrue(e.getMessage().contains("DTRON does not bundle TRON"), e.getMessage());
    }
}
